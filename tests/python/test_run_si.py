"""tribo.run_si: a real particle through the SI FMU, from the materials table to the exit."""

import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

import tribo


@pytest.mark.parametrize("version", [2, 3])
def test_polyethylene_on_steel_runs_to_the_exit(version):
    df = tribo.run_si("PE", "steel", size=1e-3, chute_length=0.05,
                      drop_height=1e-3, record_interval=1e-3, fmu=version)
    last = df.iloc[-1]
    assert last["exited"] == 1
    assert last["time"] == pytest.approx(last["exit_time"], rel=1e-12)
    assert last["x"] >= 0.05
    assert (df["time"].diff().dropna() > 0).all()
    # PE on steel charges negatively (sigma0 < 0): every charge output has its sign
    assert last["charge_to_mass_static"] < 0 and last["charge_to_mass_sliding"] < 0
    assert last["impacts"] >= 1


def test_the_versions_agree():
    kw = dict(size=1e-3, chute_length=0.05, drop_height=1e-3, record_interval=1e-3)
    a = tribo.run_si("PE", "steel", fmu=2, **kw).iloc[-1]
    b = tribo.run_si("PE", "steel", fmu=3, **kw).iloc[-1]
    for name in ("exit_time", "x", "u", "charge_to_mass_static", "charge_to_mass_sliding"):
        assert a[name] == b[name], name


def test_materials_come_in_pairs():
    with pytest.raises(ValueError, match="both a particle and a wall"):
        tribo.run_si("PE", size=1e-3)


def test_a_combination_out_of_the_model_range_is_refused_naming_the_si_inputs():
    # 10 um of PE density at 400 GPa: Gamma = 7.3e-13 < 1e-12 (tests/stability); the FMU's
    # message in the package's terms: the size as given, not the FMU's semi-major axis
    with pytest.raises(RuntimeError, match=r"Gamma = 7.3.*size = 1e-05 m") as e:
        tribo.run_si("PE", "steel", size=1e-5, youngs_modulus_particle=4e11, chute_length=0.01)
    assert "semi_major_axis" not in str(e.value) and "\n" not in str(e.value)


def test_the_stick_model_is_a_parameter_of_the_package_and_its_commands(tmp_path):
    """A flat grain placed on 5 cm of chute slides off with either stick model
    (docs/model.md §3b), making no impact; the exit times differ by 3.8e-9 relative
    (measured), held to 1.2e-8. The population command takes it through --set and refuses
    a value out of its range in one line naming it."""
    ends = {}
    for stick_model in (0, 1):
        run = tribo.run_si("PE", "steel", chute_length=0.05, drop_height=0.0, epsilon=0.3,
                           t_end=1.0, record_interval=1e-3, stick_model=stick_model,
                           outputs=["exit_time", "impacts", "exited"])
        end = run.iloc[-1]
        assert end["exited"] == 1 and end["impacts"] == 0
        ends[stick_model] = end["exit_time"]
    assert ends[0] == pytest.approx(ends[1], rel=1.2e-8)
    base = [sys.executable, "-m", "tribo", "population", "-n", "2", "--serial", "--no-plot",
            "--no-progress", "--chute-length", "0.05"]
    done = subprocess.run(base + ["--out", str(tmp_path / "a"), "--set", "stick_model=0"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert len(pd.read_csv(tmp_path / "a" / "particles.csv")) == 2
    refused = subprocess.run(base + ["--out", str(tmp_path / "b"), "--set", "stick_model=2"],
                             capture_output=True, text=True)
    assert refused.returncode != 0
    message = refused.stderr.strip().splitlines()
    assert len(message) == 1 and message[0].count("stick_model = 2") == 1, refused.stderr
    assert "0 <= stick_model <= 1" in message[0]


def test_without_a_chute_length_the_run_ends_at_the_reference_chutes_exit():
    """The SI FMU's default chute is the reference case's 0.3 m: the last row is its exit."""
    last = tribo.run_si("PE", "steel", size=1e-3, epsilon=0.6, tilt_deg=30,
                        record_interval=None).iloc[-1]
    assert (last["exited"], last["end_reason"], last["at_rest"]) == (1, 1, 0)
    assert last["x"] == pytest.approx(0.3, rel=1e-9)
    assert last["time"] == last["exit_time"] < 10.0


def test_a_grain_that_settles_ends_its_run_at_rest_in_the_last_row():
    """Tilted 0.5 degrees (tan 0.5 deg = 0.0087, below mu_roll = 0.01: the rolling resistance
    holds it) the grain settles: the run ends at rest on the chute, short of the exit and of
    the horizon."""
    df = tribo.run_si("PE", "steel", size=1e-3, epsilon=0.6, tilt_deg=0.5, record_interval=1e-2)
    last = df.iloc[-1]
    assert (last["exited"], last["at_rest"], last["end_reason"]) == (0, 1, 3)
    assert last["time"] == pytest.approx(last["rest_time"], rel=1e-12)
    assert last["time"] < 10.0 and 0 <= last["x"] < 0.3
    assert (df["at_rest"].iloc[:-1] == 0).all()  # it rests from the last row on


def test_the_outputs_si_md_names_are_the_fmus():
    # si.md said run_si gives a grain's `mass`, which no output is (issue 42): each name in
    # its paragraph on the charge outputs is an output or a parameter of the SI FMU
    import os
    import re

    from tribo.fmu.locate import find_fmu
    from tribo.fmu.names import output_names, parameter_names
    from tribo.materials import model_description
    from tribo_fmu import ROOT
    with open(os.path.join(ROOT, "docs", "si.md"), encoding="utf-8") as f:
        text = f.read()
    paragraph = text[text.index("**Charge outputs.**"):].split("\n\n")[0]
    md = model_description(find_fmu(None, variant="si"))
    known = set(output_names(md)) | set(parameter_names(md))
    names = {n.replace("<name>", "static") for n in re.findall(r"`([a-z_<>]+)`", paragraph)}
    assert len(names) >= 8 and names <= known, names - known


def test_tribo_grain_prints_the_q_per_m_run_si_gives(capsys):
    # one grain's q/m from the command line (only tribo.run_si gave it): the same run
    from tribo.cli.main import main as tribo_command
    values = dict(size=2e-3, epsilon=0.8, chute_length=0.2, tilt_deg=40, drop_height=0.02)
    assert tribo_command(["grain", "--particle", "PP", "--wall", "aluminium",
                          *[f"--{k.replace('_', '-')}={v:g}" for k, v in values.items()]]) == 0
    said = capsys.readouterr().out.splitlines()
    last = tribo.run_si("PP", "aluminium", record_interval=None, **values).iloc[-1]
    assert said[0].endswith(f"left the chute at {last['exit_time']:.4g} s at "
                            f"{float(np.hypot(last['u'], last['v'])):.4g} m/s after "
                            f"{int(last['impacts'])} impact(s)"), said
    for model in ("static", "sliding"):
        assert any(line.startswith(f"grain: {model} model: q = {last[f'charge_{model}']:.4g} C, "
                                   f"q/m = {last[f'charge_to_mass_{model}']:.4g} C/kg")
                   for line in said), said


def test_tribo_grain_meets_a_mistake_with_one_line(capsys):
    from tribo.cli.main import main as tribo_command
    assert tribo_command(["grain", "--size", "1"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("tribo grain: error: size = 1 m") and len(err.splitlines()) == 1
