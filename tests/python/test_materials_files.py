"""A materials file (tribo.materials.load, docs/materials.md) drives every job of a real
particle: run_si, a population, an impact map and the separation line take it
(`materials=`, `--materials FILE`), and its sigma0 is what their grains charge with.

The static model's charge is sigma0 times what the mechanics give (docs/model.md sections
5a, 5c, 8c: with complete transfer every band stands at sigma0) where |sigma0| is below
the gas's limit of every patch (section 8e: 4.9e-5 C/m2 and more for regions up to a
centimetre), so a pair's sigma0 doubled by a file, from 1e-5 (BASE) to 2e-5, doubles every
static charge to the rounding, the grains moving as before. (The table's 1e-3 is above the
limit: there a file's sigma0 changes nothing, section 8e.)"""

import json

import pandas as pd
import pytest

import tribo
from tribo.cli.main import main as tribo_command

DOUBLED = "[sigma0.steel]\nPE = -2e-5\nnylon = 2e-5\n\n[charging.steel.PE]\ncharging_time = 0.0\n"
BASE = "[sigma0.steel]\nPE = -1e-5\nnylon = 1e-5\n"
SHORT = {"chute_length": 0.02}


@pytest.fixture
def doubled(tmp_path):
    path = tmp_path / "doubled.toml"
    path.write_text(DOUBLED)
    return str(path)


@pytest.fixture
def base(tmp_path):
    path = tmp_path / "base.toml"
    path.write_text(BASE)
    return str(path)


def test_run_si_takes_the_files_values(doubled, base):
    kwargs = dict(size=1e-3, chute_length=0.02, t_end=1.0, record_interval=1e-2,
                  outputs=["charge_static", "exited"])
    table = tribo.run_si("PE", "steel", materials=base, **kwargs).iloc[-1]
    assert table["charge_static"] < 0
    file = tribo.run_si("PE", "steel", materials=doubled, **kwargs).iloc[-1]
    assert table["exited"] == file["exited"] == 1
    assert file["charge_static"] == pytest.approx(2 * table["charge_static"], rel=1e-12, abs=0)


def test_a_population_and_its_command_take_the_file(doubled, base, tmp_path, capsys):
    table = tribo.population(3, seed=5, chute=SHORT, t_end=1.0, serial=True, materials=base,
                             out=str(tmp_path / "table"))
    file = tribo.population(3, seed=5, chute=SHORT, t_end=1.0, serial=True, materials=doubled,
                            out=str(tmp_path / "file"))
    assert (file.results["sigma0"] == -2e-5).all() and (file.results["charging_time"] == 0).all()
    pd.testing.assert_series_equal(file.results["charge_static"],
                                   2 * table.results["charge_static"], rtol=1e-12)
    # the command: the same rows
    assert tribo_command(["population", "-n", "3", "--seed", "5", "--chute-length", "0.02",
                          "--t-end", "1", "--materials", doubled, "--serial", "--no-progress",
                          "--out", str(tmp_path / "command")]) == 0
    rows = tribo.load_results(str(tmp_path / "command"))
    assert list(rows["charge_static"]) == list(file.results["charge_static"])
    # the folder's record holds the values: the same folder with the table's is another set-up
    with open(tmp_path / "command" / "tribo.json") as f:
        feed = json.load(f)["setup"]["feed"]
        assert feed["settings"]["sigma0"] == -2e-5
        # and the file, which the figure's title names (it did not: issue 42)
        assert feed["materials"] == doubled and file.results is not None
    assert tribo_command(["population", "-n", "3", "--seed", "5", "--chute-length", "0.02",
                          "--t-end", "1", "--serial", "--no-progress",
                          "--out", str(tmp_path / "command")]) == 2
    assert "another set-up" in capsys.readouterr().err


def test_an_impact_map_takes_the_file(doubled, base, tmp_path):
    grid = dict(speed=[1.0, 2.0], angle_deg=[90.0], phi0_deg=[0.0], epsilon=[1.0])
    table = tribo.impact_map(**grid, serial=True, materials=base, out=str(tmp_path / "table"))
    file = tribo.impact_map(**grid, serial=True, materials=doubled, out=str(tmp_path / "file"))
    for speed in (1.0, 2.0):
        point = dict(speed=speed, angle_deg=90.0, phi0_deg=0.0, epsilon=1.0)
        assert file("charge_static", **point) == pytest.approx(
            2 * table("charge_static", **point), rel=1e-12, abs=0)


def test_the_line_takes_the_file_for_each_particle(doubled, base, tmp_path):
    kwargs = dict(voltage=10e3, chute={"chute_length": 0.05}, size=1e-3, epsilon=0.8)
    for particle in ("PE", "nylon"):
        table = tribo.line_grain(particle, "steel", materials=base, **kwargs)
        file = tribo.line_grain(particle, "steel", materials=doubled, **kwargs)
        assert file["charge_to_mass"] == pytest.approx(2 * table["charge_to_mass"], rel=1e-12,
                                                       abs=0)
    # a mixture: each material its own sigma0 from the file, the record names the file
    mix = tribo.line_mixture(4, seed=1, voltage=10e3, chute={"chute_length": 0.02}, t_end=1.0,
                             serial=True, materials=doubled, out=str(tmp_path / "mixture"))
    sigma0 = mix.results.groupby("particle")["sigma0"].first()
    assert sigma0["PE"] == -2e-5 and sigma0["nylon"] == 2e-5
    with open(tmp_path / "mixture" / "tribo.json") as f:
        assert json.load(f)["setup"]["line"]["materials"]["file"].endswith("doubled.toml")


def test_a_bad_materials_file_is_one_line_from_every_command(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("[sigma0.steel]\nPE = -1.0\n")
    for argv in (["population", "-n", "2"], ["impact-map", "--speed", "1", "--angle-deg", "90"],
                 ["line", "mixture", "-n", "2"], ["line", "grain"]):
        out = tmp_path / argv[0]
        assert tribo_command(argv + ["--materials", str(bad), "--serial", "--out", str(out)]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and "bad.toml" in err and "PE = -1.0" in err, err
        assert not out.exists()


@pytest.mark.parametrize("path, reason", [
    ("/dev/zero", "not a regular file"), ("/dev/null", "not a regular file"),
    ("FOLDER", "a folder, not a file"), ("MISSING", "no such file"), ("HUGE", "MiB, above the")])
def test_a_materials_or_data_path_that_is_no_file_is_refused_at_once_with_its_reason(
        tmp_path, capsys, path, reason):
    # /dev/zero was read until memory ran out; a device and a folder were "no such file"
    huge = tmp_path / "huge.csv"
    with open(huge, "wb") as f:  # sparse: no disk used
        f.truncate(65 * 2**20)
    path = {"FOLDER": str(tmp_path), "MISSING": str(tmp_path / "missing.toml"),
            "HUGE": str(huge)}.get(path, path)
    good = tmp_path / "impacts.csv"
    good.write_text("speed,angle_deg,size,epsilon,charge\n1,90,1e-3,1,-1e-14\n2,60,1e-3,0.8,-2e-14\n")
    for argv in (["population", "-n", "2", "--materials", path],
                 ["calibrate", "--impacts", str(good), "--materials", path],
                 ["calibrate", "--impacts", path],
                 ["population", "-n", "2", "--measured", path]):
        out = tmp_path / "out"
        assert tribo_command(argv + ["--serial", "--out", str(out)]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and path in err and reason in err, err
        assert not out.exists()
