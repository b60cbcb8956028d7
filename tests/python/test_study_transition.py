"""The search for the transition roundness (tribo/study/transition.py): on
synthetic predicates with a known answer, and on short real FMU runs."""

import math

import pytest

from study_support import image_of, short_spec
from tribo.batch.executors import SerialExecutor
from tribo.batch.particle import run_fmu
from tribo.batch.sweep import run_sweep
from tribo.study.transition import find_transition

# the motion alone: every charge model switched off
NO_CHARGE = dict(charge_model_static=0, charge_model_sliding=0)

GRID = [round(0.1 * k, 10) for k in range(1, 11)]
# the runs without charging (turning does not depend on it: charging does not act back)
NO_CHARGE = {"charge_model_static": 0, "charge_model_sliding": 0}


class Threshold:
    """turns(eps) = eps >= true_value, recording what is asked."""

    def __init__(self, true_value, islands=()):
        self.true_value, self.islands, self.batches = true_value, islands, []

    def __call__(self, epsilons):
        self.batches.append(list(epsilons))
        return [e >= self.true_value or any(abs(e - i) < 1e-9 for i in self.islands) for e in epsilons]


@pytest.mark.parametrize("points_per_round", [1, 2, 4])
@pytest.mark.parametrize("true_value", [0.4237, 0.8999, 0.15, 0.35])
def test_brackets_a_known_monotone_transition(true_value, points_per_round):
    width = 1e-3
    turns = Threshold(true_value)
    t = find_transition(turns, GRID, width, points_per_round)
    assert t.found and t.lo < true_value <= t.hi and t.hi - t.lo <= width * (1 + 1e-9)
    assert t.estimate - t.uncertainty == pytest.approx(t.lo) and t.uncertainty <= width / 2
    assert t.monotonic_on_grid and t.monotonic
    # the first batch is the grid, then one batch of points_per_round per round, each round
    # shrinking the bracket (0.1 wide) by points_per_round + 1
    assert turns.batches[0] == GRID
    assert all(len(b) == points_per_round for b in turns.batches[1:])
    assert t.rounds == len(turns.batches) - 1 == math.ceil(math.log(0.1 / width) / math.log(points_per_round + 1) - 1e-9)


def test_transition_on_a_grid_point():
    t = find_transition(Threshold(0.5), GRID, 0.01, 2)
    assert t.lo < 0.5 <= t.hi and t.hi == pytest.approx(0.5)


def test_reports_non_monotonic_turning_on_the_grid():
    """An island of turning at 0.2 below the transition at 0.7: the smallest turning value on
    the grid is the bracket's upper end, and the grid is flagged as non-monotonic."""
    t = find_transition(Threshold(0.7, islands=(0.2,)), GRID, 0.01, 2)
    assert not t.monotonic_on_grid and not t.monotonic
    assert 0.1 <= t.lo < t.hi == pytest.approx(0.2) and t.hi - t.lo <= 0.01


def test_no_transition_or_below_the_grid():
    none = find_transition(Threshold(2.0), GRID, 0.01)
    assert not none.found and none.hi is None and "no turning" in none.describe()
    below = find_transition(Threshold(0.0), GRID, 0.01)
    assert not below.found and below.lo is None and below.hi == pytest.approx(0.1)


def test_finds_the_high_friction_transition_of_the_fmu(fmu_file, tmp_path):
    """High friction, tau to 200: at the grid 0.1 ... 0.5 the turning starts between 0.3 and
    0.4, as in the full study (eps_t = 0.339 at tau = 5000). The bracket's ends, run again
    on their own, are on the sides they are said to be on."""
    image = image_of(fmu_file)
    path = str(tmp_path / "results.csv")

    def turns(epsilons):
        with SerialExecutor() as ex:
            report = run_sweep([short_spec(e, "high", **NO_CHARGE) for e in epsilons], image, path,
                               ex, progress=False)
        return [bool(v) for v in report.results["turned_over"]]

    t = find_transition(turns, [0.1, 0.3, 0.5], width=0.02, points_per_round=2)
    assert t.found and 0.3 <= t.lo < t.hi <= 0.4 and t.hi - t.lo <= 0.02 + 1e-12
    assert t.monotonic
    lo, hi = (run_fmu(image, short_spec(e, "high", **NO_CHARGE)).row for e in (t.lo, t.hi))
    assert lo["turns_max"] < 0.5 <= hi["turns_max"]
