"""FMU instances kept across the runs of a task (fmu/reuse.py): a run on a kept instance,
reset after other runs, is a run on a new instance to the bit (FMI 2.0 and 3.0: a chute's
grain, an impact episode, a line's grain); a failed run's instance is not handed out again;
the executors give each task one set of instances; the runs' keys are those of the text
read back and written again."""

import hashlib
import json
import math

import numpy as np
import pytest

import tribo
import tribo.fmu.reuse as reuse_module
from tribo.batch.executors import SerialExecutor, run_each
from tribo.batch.specs import RunSpec, run_key
from tribo.fmu import FmuImage, Instance
from tribo.fmu.reuse import Instances
from tribo.impact.episode import Grid, episode_specs, run_episode
from tribo.line.grain import load_images, run_line_grain
from tribo.line.mixture import Line, line_specs
from tribo.populations.feed import Feed
from tribo.populations.particle import run_particle
from tribo.populations.runner import prepare_population

TIMINGS = ("cpu_s", "wall_s", "chute_cpu_s")
VERSIONS = [2, 3]


def image_of(version):
    return FmuImage.load(tribo.find_fmu(version, variant="si"))


def bits(row: dict) -> dict:
    """A row's values but the timings, each with its type and its bits (-0.0 is not 0.0,
    NaN is NaN)."""
    return {k: (type(v), np.float64(v).view(np.int64) if isinstance(v, float) else v)
            for k, v in row.items() if k not in TIMINGS}


def episodes(image):
    grid = Grid.of(speed=[0.5, 3.0], angle_deg=[20.0, 90.0], phi0_deg=[0.0, 60.0],
                   epsilon=[0.5, 1.0])
    return episode_specs(grid, "PE", "steel", {}, 200.0)


def grains(image):
    return prepare_population(Feed(chute={"chute_length": 0.02}), 4, 3, 1.0, image)


@pytest.mark.parametrize("version", VERSIONS)
def test_runs_on_kept_instances_are_runs_on_new_ones_to_the_bit(version):
    """Episodes and grains in turn through one Instances (each kind's instance reset
    between its runs, the other kind's runs in between) against each run on an instance
    of its own."""
    image = image_of(version)
    runs = [(run_episode, s) for s in episodes(image)] + [(run_particle, s) for s in grains(image)]
    runs = [runs[i] for i in np.random.default_rng(1).permutation(len(runs))]
    with Instances() as instances:
        kept = [run(image, spec, instances).row for run, spec in runs]
    for (run, spec), row in zip(runs, kept):
        assert bits(row) == bits(run(image, spec).row), (run.__name__, spec.params)


@pytest.mark.parametrize("version", VERSIONS)
def test_a_lines_grains_on_kept_instances_are_the_grains_alone_to_the_bit(version):
    images = load_images(version, version, {}, [5e3, 40e3])
    specs = line_specs(Line(chute={"chute_length": 0.05}), 4, 2, 5.0, images.models,
                       images.chute.model_description())
    with Instances() as instances:
        kept = [run_line_grain(images, spec, instances) for spec in specs]
    for spec, result in zip(specs, kept):
        alone = run_line_grain(images, spec)
        assert bits(result.row) == bits(alone.row)
        assert list(result.series) == list(alone.series)
        for name in alone.series:
            assert result.series[name].dtype == alone.series[name].dtype
            assert result.series[name].tobytes() == alone.series[name].tobytes(), name


class Counted(Instance):
    made = freed = 0

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        Counted.made += 1

    def free(self):
        super().free()
        Counted.freed += 1


@pytest.fixture
def counted(monkeypatch):
    monkeypatch.setattr(reuse_module, "Instance", Counted)
    Counted.made = Counted.freed = 0
    return Counted


def test_a_failed_runs_instance_is_freed_and_the_next_run_is_a_new_ones(counted):
    image = image_of(3)
    good = episodes(image)[:3]
    bad = RunSpec(dict(good[0].params, size=-1.0), good[0].t_end, good[0].record_interval)
    with Instances() as instances:
        first = run_episode(image, good[0], instances)
        with pytest.raises(RuntimeError, match="size"):
            run_episode(image, bad, instances)
        assert (counted.made, counted.freed) == (1, 1)
        after = [run_episode(image, spec, instances) for spec in good[1:]]
        assert (counted.made, counted.freed) == (2, 1)
    assert (counted.made, counted.freed) == (2, 2)
    for spec, result in zip(good, [first] + after):
        assert bits(result.row) == bits(run_episode(image, spec).row)


def test_the_executors_give_a_task_one_instance_and_free_it(counted):
    """A Dask task (run_each) and a serial sweep: one instance for all their runs, freed
    at their end; a failed run among them is the run's outcome, not the task's."""
    image = image_of(3)
    specs = episodes(image)[:4]
    bad = RunSpec(dict(specs[0].params, size=-1.0), specs[0].t_end, specs[0].record_interval)
    results = run_each(run_episode, image, specs)
    assert (counted.made, counted.freed) == (1, 1)
    assert all(not isinstance(r, BaseException) for r in results)
    with SerialExecutor() as executor:
        outcomes = dict(executor.run(run_episode, image, specs[:2] + [bad] + specs[2:]))
    assert isinstance(outcomes[2], RuntimeError)
    assert (counted.made, counted.freed) == (3, 3)  # the failed run's, then a new one
    rows = [outcomes[i].row for i in (0, 1, 3, 4)]
    assert [bits(r) for r in rows] == [bits(r.row) for r in results]


def test_a_runs_key_is_that_of_its_text_read_back_and_written_again():
    """run_key hashes the spec's JSON text in one json.dumps: the same key as the text of
    json.loads(spec.as_json()) (the key every results file holds), for the specs of a map,
    a population and a line and for values whose text is unusual."""
    def read_back_key(spec, sha256):
        text = json.dumps({"fmu": sha256, "run": json.loads(spec.as_json())}, sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    image = image_of(3)
    images = load_images(3, 3, {}, [5e3])
    specs = episodes(image) + grains(image) + line_specs(
        Line(), 5, 1, 5.0, images.models, images.chute.model_description())
    specs.append(RunSpec({"a": math.nan, "b": -0.0, "c": True, "d": "Pé, \"x\"", "e": 10 ** 20,
                          "f": 1e-300, "g": math.inf, "h": (1, 2.5)}, 1.0, 0.1))
    for spec in specs:
        assert run_key(spec, image.sha256) == read_back_key(spec, image.sha256)
