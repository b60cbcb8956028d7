"""One FMU run as the study makes it (tribo/batch/particle.py and summary.py):
the recorded series and the summary row agree with each other and with the FMU."""

import numpy as np
import pytest

from study_support import image_of, short_spec
from tribo.batch.particle import recorded, run_fmu
from tribo.batch.summary import (MOTION_CLASSES, WARMUP, bounce_envelope, report_times,
                                 summary_columns, upper_envelope)


@pytest.fixture(scope="module")
def tumbling_run(fmu_file):
    """The disc at low friction: tumbling and bouncing after the warm-up (a mix of modes)."""
    return run_fmu(image_of(fmu_file), short_spec(1.0, "low", t_end=400.0))


def test_series_is_recorded_at_every_interval(tumbling_run):
    s = tumbling_run.series
    assert list(s.columns) == ["time"] + recorded(("static", "sliding"))
    assert np.array_equal(s["time"].to_numpy(), np.arange(401.0))
    assert s["Q_static"].is_monotonic_increasing  # model.md § 6: Q_static never decreases


def test_summary_row_has_its_columns_in_order(tumbling_run):
    assert list(tumbling_run.row) == summary_columns(("static", "sliding")) + ["cpu_s", "wall_s"]
    assert report_times(5000.0) == [1000.0, 2000.0, 3000.0, 4000.0, 5000.0]
    s = tumbling_run.series.set_index("time")
    assert tumbling_run.row["Q_static_end"] == s.loc[400.0, "Q_static"]
    assert tumbling_run.row["Q_sliding_40pct"] == s.loc[160.0, "Q_sliding"]
    assert tumbling_run.row["cpu_s"] > 0 and tumbling_run.row["wall_s"] > 0


def test_mode_fractions_sum_to_one(tumbling_run):
    row = tumbling_run.row
    assert sum(row[f"fraction_{m}"] for m in MOTION_CLASSES) == pytest.approx(1.0, abs=1e-9)
    assert sum(row[f"fraction_{m}_after_warmup"] for m in MOTION_CLASSES) == pytest.approx(1.0, abs=1e-9)
    # the case mixes modes, so the check above is not 1 = 1 + 0 + 0 ...
    assert row["fraction_tumbling_after_warmup"] > 0.1 and row["fraction_bouncing_after_warmup"] > 0.1


def test_mode_fractions_agree_with_the_sampled_mode(tumbling_run):
    """The after-warm-up fractions (from the FMU's cumulative mode times) against the share
    of recorded times in each motion_class: equal up to the sampling (a few switches)."""
    s = tumbling_run.series
    after = s[s["time"] > WARMUP]
    for i, m in enumerate(MOTION_CLASSES):
        sampled = float((after["motion_class"] == i).mean())
        assert tumbling_run.row[f"fraction_{m}_after_warmup"] == pytest.approx(sampled, abs=0.02), m


def test_contact_statistics_are_consistent(tumbling_run):
    row, s = tumbling_run.row, tumbling_run.series
    assert 0 < row["contact_fraction"] < 1
    assert row["contact_fraction"] == pytest.approx(s["in_contact"].mean(), abs=0.02)
    # flight (no contact within the window) is part of the time out of contact
    assert row["fraction_flight"] <= 1 - row["contact_fraction"] + 1e-9
    assert row["turns"] == s["turns"].iloc[-1] and row["turns_max"] >= row["turns"]
    assert row["turned_over"] == int(row["turns_max"] >= 0.5) == 1


def test_bounce_envelope_bounds_y(tumbling_run):
    s = tumbling_run.series
    y, env = s["Y"].to_numpy(), bounce_envelope(s)
    assert np.all(env >= y)
    # it is the maximum over the centred 51-sample window (50 time units at interval 1)
    for i in (0, 10, 200, len(y) - 1):
        assert env[i] == y[max(0, i - 25): i + 26].max()
    assert tumbling_run.row["Y_max"] == env.max() == y.max()
    assert tumbling_run.row["bounce_amplitude_end"] == env[-1]
    assert env.max() > env.min()  # the disc bounces: the envelope is not flat


def test_upper_envelope_on_a_known_signal():
    y = np.array([0.0, 3.0, 1.0, 0.0, 0.0, 2.0, 0.0])
    assert upper_envelope(y, 3).tolist() == [3.0, 3.0, 3.0, 1.0, 2.0, 2.0, 2.0]
    assert upper_envelope(y, 1).tolist() == y.tolist()


def test_fmi2_and_fmi3_give_the_same_run(fmu_file):
    spec = short_spec(0.6, "high", t_end=50.0)
    a, b = run_fmu(image_of(fmu_file, 2), spec), run_fmu(image_of(fmu_file, 3), spec)
    assert a.series.equals(b.series)
    # the FMI 3.0 FMU's arrays give each segment's charge at the end; their mean is the output
    assert a.segments is None and len(b.segments) == 64
    assert b.segments["static"].mean() == pytest.approx(b.series["Q_static"].iloc[-1], rel=1e-12)
    assert b.segments["sliding"].mean() == pytest.approx(b.series["Q_sliding"].iloc[-1], rel=1e-12)
    assert {k: v for k, v in a.row.items() if k not in ("cpu_s", "wall_s")} == \
           {k: v for k, v in b.row.items() if k not in ("cpu_s", "wall_s")}


def test_a_parameter_changes_the_run(fmu_file):
    """(So that equal results elsewhere mean something: the spec reaches the FMU.)"""
    image = image_of(fmu_file)
    a = run_fmu(image, short_spec(0.6, "high", t_end=20.0))
    b = run_fmu(image, short_spec(0.6, "high", t_end=20.0, eta=0.5))
    assert a.row["Q_static_end"] == b.row["Q_static_end"]  # eta acts on the sliding model only
    assert a.row["Q_sliding_end"] != b.row["Q_sliding_end"]


def test_an_unknown_parameter_is_refused(fmu_file):
    with pytest.raises(ValueError, match="not parameters of the FMU: roundness"):
        run_fmu(image_of(fmu_file), short_spec(0.6, "high", t_end=5.0, roundness=0.5))


def test_fmu_messages_are_kept_not_printed(fmu_file, capfd):
    """The FMU's warnings (deep indentation at nu = 1 with the centre dashpot) are counted,
    not printed per run."""
    r = run_fmu(image_of(fmu_file), short_spec(0.5, "high", t_end=100.0, damping_point=1))
    assert r.row["assumption_warnings"] > 0
    out, err = capfd.readouterr()
    assert "assumption" not in out + err


@pytest.mark.parametrize("version", [2, 3])
def test_a_refused_value_fails_with_the_fmus_reason(fmu_file, version):
    with pytest.raises(RuntimeError, match=r"setting the parameters: rtol = -1 is invalid: the "
                                           r"valid range is 1e-14 <= rtol < 1$"):
        run_fmu(image_of(fmu_file, version), short_spec(0.6, "high", t_end=5.0, rtol=-1.0))
