"""The separation line (tribo.line, docs/line.md): one grain down the SI chute and through
the separator lands on its charge's side and exactly where a direct fmpy two-step puts it;
a mixture's masses add up to the fed mass, its grade and recovery are those of the masses;
a voltage sweep runs the chute once per grain; the command runs, and refuses a bad value in
one line naming it; its --help examples run (at a small size)."""

import math
import os
import shlex
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

import tribo
import tribo.line.grain as grain_module
from tribo.batch.executors import SerialExecutor
from tribo.line.grain import load_images
from tribo.line.mixture import Line, check_line, line_specs, run_line
from tribo_fmu import Slave

PYTHON = sys.executable
ENV = dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in sys.path if p))
# the reference chute: the grain (the spheroid, sliding model) leaves it at a few 1e-7 C/kg
SHORT = {"chute_length": 0.3}


def direct_two_step(fmu_dir, particle, wall, voltage, size=1e-3, epsilon=0.6, t_end=5.0):
    """The line written out with the package's fmpy driver: the SI chute on the population's
    grid (t_end / 100) to its exit, then the separator held to the exit time, released with
    the chute's outputs there, one step to its end."""
    from tribo.materials import pair_values
    chute = Slave(fmu_dir(3, "tribo_si"), 3, name="chute")
    chute.init(0.0, t_end, **pair_values(particle, wall), semi_major_axis=size / 2,
               epsilon=epsilon, chute_length=SHORT["chute_length"], tilt=math.radians(30),
               drop_height=0.01, drop_speed=0.0, drop_angle=0.0, phi0=0.0, omega0=0.0,
               work_limit=2**31 - 1, charge_model_static=0, charge_model_sliding=1,
               charge_to_mass_model=2)
    times = [i * t_end / 100 for i in range(1, 100)] + [t_end]
    assert not all(chute.step_to(t) for t in times), "the grain does not leave the chute"
    t_exit = chute.t
    sep = Slave(fmu_dir(3, "tribo_separator"), 3, name="separator")
    sep.init(0.0, None, tilt=chute.get("tilt"), semi_major_axis=size / 2, epsilon=epsilon,
             density=chute.get("density"), gravity=chute.get("gravity"), voltage=voltage)
    sep.step_to(t_exit)
    sep.set(released=chute.get("exited"), u_entry=chute.get("u"), v_entry=chute.get("v"),
            charge_to_mass=chute.get("charge_to_mass"))
    assert not sep.step_to(t_exit + 10.0)
    return chute.get("charge_to_mass"), sep.get_many(["bin", "x_end", "electrode", "landed",
                                                      "flight_time"]), sep.t


@pytest.mark.parametrize("particle, sign", [("PE", -1), ("nylon", 1)])
def test_one_grain_lands_on_its_charges_side_as_the_direct_two_step(fmu_dir, particle, sign):
    g = tribo.line_grain(particle, "steel", voltage=10e3, chute=SHORT, charge_model="sliding")
    assert g["exited"] == 1 and g["landed"] == 1 and g["electrode"] == 0
    assert math.copysign(1, g["charge_to_mass"]) == sign and abs(g["charge_to_mass"]) > 1e-7
    # U > 0: a positive grain drifts to -x, into the bins from the negative plate's side
    assert math.copysign(1, g["x_end"]) == -sign
    assert (g["bin"] <= 5) == (sign > 0)
    q, landing, t_land = direct_two_step(fmu_dir, particle, "steel", 10e3)
    assert g["charge_to_mass"] == q
    assert (g["bin"], g["x_end"], g["electrode"], g["flight_time"]) == \
        (landing["bin"], landing["x_end"], landing["electrode"], landing["flight_time"])
    assert g["time_land"] == t_land


def test_the_static_model_is_the_default_and_one_model_only():
    g = tribo.line_grain("PE", "steel", voltage=10e3, chute=SHORT)
    assert g["charge_to_mass_sliding"] == 0.0 and g["charge_to_mass"] == g["charge_to_mass_static"]
    with pytest.raises(ValueError, match="charge_model = 'both'"):
        tribo.line_grain("PE", "steel", charge_model="both")


N = 20


@pytest.fixture(scope="module")
def sweep(tmp_path_factory, monkeypatch_module):
    """A 20-grain PE + nylon mixture at three voltages, serial, counting the chute runs."""
    calls = []
    original = grain_module.run_particle

    def counted(image, spec, *instances):
        calls.append(spec)
        return original(image, spec, *instances)

    monkeypatch_module.setattr(grain_module, "run_particle", counted)
    out = str(tmp_path_factory.mktemp("line") / "sweep")
    report = tribo.line_sweep(N, seed=3, voltages=[5e3, 20e3, 40e3], chute={"chute_length": 0.1},
                              out=out, serial=True)
    return report, calls, out


@pytest.fixture(scope="module")
def monkeypatch_module():
    mp = pytest.MonkeyPatch()
    yield mp
    mp.undo()


def test_the_sweep_runs_the_chute_once_per_grain(sweep):
    report, calls, out = sweep
    assert len(calls) == N  # not N x 3
    assert len(report.results) == N and len(report.landings) == 3 * N
    assert sorted(report.table["voltage"]) == [5e3, 20e3, 40e3]
    assert {"particles.csv", "landings.csv", "line.csv", "bins.csv", "line.png"} <= set(os.listdir(out))


def test_the_mixtures_masses_add_up_and_grade_and_recovery_are_theirs(sweep):
    report, _, _ = sweep
    rows = report.results
    fed = rows.groupby("particle")["mass"].sum()
    regions = ("left", "right", "plate_neg", "plate_pos", "airborne", "not_exited")
    for _, row in report.table.iterrows():
        for m in ("PE", "nylon"):
            assert row[f"fed_{m}"] == pytest.approx(fed[m], rel=1e-12)
            assert sum(row[f"{r}_{m}"] for r in regions) == pytest.approx(fed[m], rel=1e-12)
        # U > 0: nylon (positive on steel) is the -x product's target, PE the +x one's
        nylon_product = row["left_nylon"] + row["plate_neg_nylon"]
        neg_side = nylon_product + row["left_PE"] + row["plate_neg_PE"]
        pe_product = row["right_PE"] + row["plate_pos_PE"]
        pos_side = pe_product + row["right_nylon"] + row["plate_pos_nylon"]
        assert row["grade_nylon"] == pytest.approx(nylon_product / neg_side, rel=1e-12)
        assert row["recovery_nylon"] == pytest.approx(nylon_product / fed["nylon"], rel=1e-12)
        assert row["grade_PE"] == pytest.approx(pe_product / pos_side, rel=1e-12)
        assert row["recovery_PE"] == pytest.approx(pe_product / fed["PE"], rel=1e-12)
        for c in ("grade_PE", "grade_nylon", "recovery_PE", "recovery_nylon"):
            assert 0 <= row[c] <= 1
    bins = report.bins
    landed = report.landings[report.landings["landed"] == 1]
    assert bins["mass"].sum() == pytest.approx(landed["mass"].sum(), rel=1e-12)


def test_the_mixtures_fed_fraction_follows_the_mass_fraction():
    line = Line(("PE", "nylon"), fraction=0.5)
    specs = line_specs(line, 1000, 0, 5.0, ("static", "sliding"))
    n_pe = sum(s.params["particle"] == "PE" for s in specs)
    assert n_pe == round(1000 * (0.5 / 950) / (0.5 / 950 + 0.5 / 1140))
    assert all(abs(s.params["x_entry"]) <= 0.005 for s in specs)


def test_a_pair_of_one_polarity_is_refused():
    with pytest.raises(ValueError, match="same sign on steel"):
        Line(("PE", "PP")).check()


def test_a_resumed_folder_runs_nothing_again(tmp_path):
    line = Line(("PE", "nylon"), chute={"chute_length": 0.05, "tilt_deg": 30.0})
    images = load_images(None, None, {}, [10e3])
    specs = line_specs(line, 4, 0, 5.0, images.models)
    check_line(line, specs, images)
    first = run_line(line, 4, 0, 5.0, images, str(tmp_path), SerialExecutor(), specs=specs,
                     progress=False)
    again = run_line(line, 4, 0, 5.0, images, str(tmp_path), SerialExecutor(), specs=specs,
                     progress=False)
    assert (first.executed, again.executed, again.skipped) == (4, 0, 4)
    pd.testing.assert_frame_equal(first.table, again.table)


def cli(*args, cwd):
    return subprocess.run([PYTHON, "-m", "tribo", "line", *args], cwd=cwd, capture_output=True,
                          text=True, env=ENV, timeout=300)


def test_the_command_runs_a_grain_and_a_mixture(tmp_path):
    done = cli("grain", "--particle", "nylon", "--chute-length", "0.05", "--charge-model",
               "sliding", "--voltage", "10e3", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert "landed in bin" in done.stdout
    done = cli("mixture", "-n", "6", "--chute-length", "0.05", "--serial", "--no-progress",
               "--out", "m", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    table = pd.read_csv(tmp_path / "m" / "line.csv")
    assert list(table["voltage"]) == [30e3]


@pytest.mark.parametrize("args, text", [
    (["grain", "--voltage", "2e7"], "voltage = 20000000 is invalid"),
    (["mixture", "--fraction", "1.5"], "fraction = 1.5"),
    (["sweep", "--voltages", "5e3:x:3"], "--voltages 5e3:x:3"),
    (["mixture", "--particles", "PE,PP"], "same sign"),
    (["grain", "--separator", "gap=1e-5"], "gap = 1e-05 is invalid"),
    (["grain", "--size", "0.2"], "size = 0.2 m does not fit the gap"),
    (["mixture", "--charge-model", "both"], "charge_model = 'both': one of static, sliding"),
])
def test_a_bad_value_is_refused_in_one_line_naming_it(tmp_path, args, text):
    done = cli(*args, cwd=tmp_path)
    assert done.returncode == 2
    assert len(done.stderr.strip().splitlines()) == 1 and text in done.stderr, done.stderr
    assert "Traceback" not in done.stderr


def help_examples() -> list[str]:
    text = subprocess.run([PYTHON, "-m", "tribo", "line", "--help"], capture_output=True,
                          text=True, env=ENV, check=True, timeout=60).stdout
    return [line.strip() for line in text.splitlines() if line.startswith("    tribo line ")]


def test_each_help_example_runs_at_a_small_size(tmp_path):
    """Each example of --help, shrunk: 4 grains, 2 voltages, a 5 cm chute."""
    examples = help_examples()
    assert len(examples) >= 4
    for line in examples:
        argv = shlex.split(line)[2:]
        if "-n" in argv:
            argv[argv.index("-n") + 1] = "4"
        if "--voltages" in argv:
            argv[argv.index("--voltages") + 1] = "5e3:40e3:2"
        argv = [a for a in argv if a != "--workers" and a != "2"] + ["--chute-length", "0.05"]
        if argv[0] != "grain":
            argv += ["--serial", "--no-progress"]
        done = cli(*argv, cwd=tmp_path)
        assert done.returncode == 0, f"{line}:\n{done.stderr[-2000:]}"


def test_a_grain_at_rest_on_the_chute_never_enters_the_separator(capsys):
    g = tribo.line_grain("nylon", "steel", voltage=10e3, chute={"tilt_deg": 0.5})
    assert (g["exited"], g["at_rest"], g["end_reason"]) == (0, 1, 3)
    assert 0 < g["rest_time"] == g["time_end"] < 5.0
    assert (g["landed"], g["electrode"], g["bin"]) == (0, 0, 0)
    from tribo.cli.main import main as tribo_command
    assert tribo_command(["line", "grain", "--particle", "nylon", "--tilt-deg", "0.5",
                          "--voltage", "10e3"]) == 0
    said = capsys.readouterr().out
    assert f"the grain came to rest on the chute at {g['rest_time']:.6g} s: it does not enter " \
           "the separator" in said


def test_grains_that_stay_on_the_chute_are_counted_apart_in_the_line(tmp_path, capsys):
    """Tilted 5 degrees with a 1.5 s horizon, seed 0's six grains: some come to rest, some
    are still on the chute at the horizon (seen in the run); line.csv counts each apart, by
    material, with its mass, and the closing line says so."""
    from tribo.cli.main import main as tribo_command
    out = tmp_path / "m"
    assert tribo_command(["line", "mixture", "-n", "6", "--tilt-deg", "5", "--t-end", "1.5",
                          "--serial", "--no-progress", "--out", str(out)]) == 0
    said = capsys.readouterr().out
    rows = pd.read_csv(out / "particles.csv")
    table = pd.read_csv(out / "line.csv").iloc[0]
    assert set(rows["end_reason"]) >= {0, 3}  # both ways of staying occur
    for m in ("PE", "nylon"):
        g = rows[rows["particle"] == m]
        rest, horizon = g[g["end_reason"] == 3], g[g["end_reason"] == 0]
        assert (table[f"n_fed_{m}"], table[f"n_at_rest_{m}"], table[f"n_at_horizon_{m}"]) == \
            (len(g), len(rest), len(horizon))
        assert table[f"at_rest_{m}"] == pytest.approx(rest["mass"].sum(), rel=1e-9)
        assert table[f"at_horizon_{m}"] == pytest.approx(horizon["mass"].sum(), rel=1e-9)
        assert table[f"not_exited_{m}"] == pytest.approx(
            table[f"at_rest_{m}"] + table[f"at_horizon_{m}"], rel=1e-12)
        share = 100 * rest["mass"].sum() / table[f"fed_{m}"]
        assert (f"{m}: {len(g)} grains fed, {len(rest)} at rest on the chute ({share:.3g} % of "
                f"its mass)") in said
    # a grain that stayed on the chute lands nowhere at any voltage
    landings = pd.read_csv(out / "landings.csv")
    stayed = landings[landings["exited"] == 0]
    assert len(stayed) and (stayed[["landed", "electrode"]] == 0).all().all()
    assert "these do not enter the separator" in said
    # the figure's title says the same, and its right panel draws each material's share
    from tribo.line import plot as line_plot
    from tribo.line.mixture import stayed_text
    from figure_checks import assert_legends_cover_no_data
    figures = []
    original = line_plot.save
    line_plot.save = lambda fig, path: figures.append(fig) or path
    try:
        text = stayed_text(table, ["PE", "nylon"], 1.5, sep="\n")
        line_plot.write_line_figure(pd.read_csv(out / "line.csv"), Line(("PE", "nylon")), 6, 0,
                                    "unused.png", text)
    finally:
        line_plot.save = original
    fig = figures[0]
    assert fig._suptitle.get_text().endswith(f"(never in the separator):\n{text}")
    for m in ("PE", "nylon"):
        share = next(line for line in fig.axes[1].get_lines()
                     if line.get_label() == f"{m} stayed on the chute")
        assert share.get_ydata()[0] == pytest.approx(table[f"not_exited_{m}"] / table[f"fed_{m}"])
    assert_legends_cover_no_data(fig)


def test_a_sweep_says_how_far_from_no_separation_and_a_missing_material_warns_nothing(tmp_path,
                                                                                       capsys):
    import warnings

    from tribo.cli.main import main as tribo_command
    argv = ["line", "sweep", "--voltages", "5e3,40e3", "--chute-length", "0.05", "--serial",
            "--no-progress", "--no-plot"]
    with warnings.catch_warnings():
        # one grain: the material that drew none gave numpy's 0/0 RuntimeWarning (issue 42)
        warnings.simplefilter("error", RuntimeWarning)
        assert tribo_command(argv + ["-n", "1", "--out", str(tmp_path / "one")]) == 0
    said = capsys.readouterr().out
    assert "0 for a random split of the feed" in said and "none: a material drew no grain" in said
    assert tribo_command(argv + ["-n", "4", "--out", str(tmp_path / "four")]) == 0
    said = capsys.readouterr().out
    table = pd.read_csv(tmp_path / "four" / "line.csv")
    recoveries = table["recovery_PE"] + table["recovery_nylon"]
    # line.csv holds 10 significant digits: 1 + 0.8775272784 - 1 is not 0.8775272784 in binary
    assert np.allclose(table["separation"], recoveries - 1, rtol=0, atol=2e-10)
    fed = table["fed_PE"][0] + table["fed_nylon"][0]
    assert f"(PE {table['fed_PE'][0] / fed:.3g}, nylon {table['fed_nylon'][0] / fed:.3g})" in said


@pytest.mark.parametrize("mode", ["grain", "mixture"])
def test_a_horizon_the_model_cannot_resolve_is_one_line_before_any_run(tmp_path, capsys, mode):
    # every grain's run failed at its first step, in a started folder (issue 42)
    from tribo.cli.main import main as tribo_command
    out = tmp_path / "l"
    assert tribo_command(["line", mode, "-n", "2", "--t-end", "1e308", "--serial",
                          "--no-progress", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "t_end = 1e+308 s: at most" in err and len(err.strip().splitlines()) == 1, err
    assert not out.exists()


# ---- the fast paths (docs/line.md, "Benchmark"), each against the path it replaced ----------

def collect_landings_file_by_file(results, landings_dir):
    """The landings as the line collected them before: each grain's file read by pandas, its
    columns inserted, the frames concatenated."""
    from tribo.batch.sweep import read_series
    frames = []
    for _, row in results.iterrows():
        df = read_series(landings_dir, row["key"])
        df.insert(0, "key", row["key"])
        df.insert(1, "particle", row["particle"])
        df.insert(2, "mass", row["mass"])
        df.insert(3, "exited", int(row["exited"]))
        df.insert(4, "end_reason", row["end_reason"] if "end_reason" in row else np.nan)
        frames.append(df)
    return pd.concat(frames, ignore_index=True)


def assert_same_to_the_bit(a: pd.DataFrame, b: pd.DataFrame):
    pd.testing.assert_frame_equal(a, b, check_exact=True)  # the columns, their types, values
    for c in a.columns:
        if a[c].dtype == np.float64:  # and the floats' bits (-0.0 is not 0.0, NaN is NaN)
            assert (a[c].to_numpy().view(np.int64) == b[c].to_numpy().view(np.int64)).all(), c


def test_the_landings_read_at_once_are_those_read_file_by_file(sweep, tmp_path):
    report, _, out = sweep
    landings_dir = os.path.join(out, "landings")
    from tribo.line.mixture import collect_landings
    assert_same_to_the_bit(collect_landings(report.results, landings_dir),
                           collect_landings_file_by_file(report.results, landings_dir))
    # where the files' headers differ (other columns), each is read alone, as before
    odd = tmp_path / "landings"
    odd.mkdir()
    keys = list(report.results["key"][:3])
    for i, key in enumerate(keys):
        text = open(os.path.join(landings_dir, f"{key}.csv")).read()
        (odd / f"{key}.csv").write_text(text.replace("landed", "landed_at") if i == 1 else text)
    from tribo.batch.sweep import read_many_series, read_series
    frame, lengths = read_many_series(str(odd), keys)
    assert_same_to_the_bit(frame, pd.concat([read_series(str(odd), k) for k in keys],
                                            ignore_index=True))
    assert lengths == [3, 3, 3]


@pytest.mark.parametrize("columns", [
    {"voltage": [5e3, 2e4, -0.0], "landed": [1, 0, 1], "x_end": [1e-300, np.nan, -2.5e-3],
     "time_land": [np.inf, -np.inf, 0.1 + 0.2]},
    {"a b": [1.0], "c,d": [2], 'e"f': [np.nan]},  # names that need quoting
    {"t": np.linspace(0, 1, 7) ** 3, "n": np.arange(7, dtype=np.int64) - 3},
])
def test_a_series_written_without_pandas_is_the_bytes_pandas_writes(columns, tmp_path):
    from tribo.batch.results import table_csv
    from tribo.batch.sweep import SERIES_FLOAT_FORMAT, write_series
    frame = pd.DataFrame({k: np.asarray(v) for k, v in columns.items()})
    expected = frame.to_csv(index=False, float_format=SERIES_FLOAT_FORMAT)
    assert table_csv(frame, SERIES_FLOAT_FORMAT) == expected
    assert table_csv({k: np.asarray(v) for k, v in columns.items()}, SERIES_FLOAT_FORMAT) == expected
    write_series({k: np.asarray(v) for k, v in columns.items()}, str(tmp_path / "s.csv"))
    assert (tmp_path / "s.csv").read_text() == expected
    # what it does not take (text, other types) pandas writes
    assert table_csv(frame.assign(text="x"), SERIES_FLOAT_FORMAT) is None
    write_series(frame.assign(text="x"), str(tmp_path / "t.csv"))
    assert (tmp_path / "t.csv").read_text() == frame.assign(text="x").to_csv(
        index=False, float_format=SERIES_FLOAT_FORMAT)


def same_bits(a: dict, b: dict) -> bool:
    """The same keys, and values of the same type and bits (-0.0 is not 0.0, NaN is NaN)."""
    def bits(x):
        return np.float64(x).view(np.int64) if isinstance(x, float) else x
    return list(a) == list(b) and all(type(a[k]) is type(b[k]) and bits(a[k]) == bits(b[k])
                                      for k in a)


@pytest.mark.parametrize("version", [2, 3])
def test_a_grains_flights_on_one_instance_are_flys_to_the_bit(version, monkeypatch):
    """Flights (one instance reset between flights, values set and read at once) against
    fly (an instance per flight, values by name): each flight of a few grains of a mixture,
    at three voltages, and the flights of a grain never released, from t = 0 and later."""
    images = load_images(version, version, {}, [5e3, 20e3, 40e3])
    specs = line_specs(Line(chute={"chute_length": 0.1}), 6, 3, 5.0, images.models,
                       images.chute.model_description())
    flown = []
    original = grain_module.Flights.fly

    def recorded(self, values, t_exit, inputs):
        out = original(self, values, t_exit, inputs)
        flown.append((list(self.parameters.names), list(values), t_exit, inputs, out))
        return out

    monkeypatch.setattr(grain_module.Flights, "fly", recorded)
    for spec in specs:
        grain_module.run_line_grain(images, spec)
    assert len(flown) == 6 * 3 and all(f[3] is not None for f in flown)
    names, values, t_exit, inputs, _ = flown[0]
    with grain_module.Flights(images.separator, names) as flights:  # never released
        for t in (0.0, t_exit):
            flown.append((names, values, t, None, original(flights, values, t, None)))
    for names, values, t_exit, inputs, out in flown:
        released = None if inputs is None else dict(zip(grain_module.INPUTS, inputs))
        expected = grain_module.fly(images.separator, dict(zip(names, values)), t_exit, released)
        assert same_bits(out, expected), (out, expected)
