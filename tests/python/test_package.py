"""The Python package tribo: installed in the venv in editable mode (the checkout's
python/tribo), imported without any sys.path manipulation, its console commands, its API
(one particle as a DataFrame, a sweep, its results) and where it finds the FMUs."""

import glob
import hashlib
import importlib
import importlib.metadata
import os
import re
import subprocess
import sys
import tomllib

import numpy as np
import pandas as pd
import pytest
from fmpy import read_model_description, simulate_fmu

import tribo
from study_support import command, subcommand
from tribo.fmu import model_description
from tribo.fmu.locate import VARIANTS, build_dir
from tribo.fmu.parameters import ParameterError
from tribo_fmu import ROOT


def test_the_venv_imports_the_checkouts_package(tmp_path):
    assert tribo.__file__ == os.path.join(ROOT, "python", "tribo", "__init__.py")
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    done = subprocess.run([sys.executable, "-c", "import tribo; print(tribo.__file__)"], cwd=tmp_path,
                          env=env, capture_output=True, text=True, check=True)
    assert done.stdout.strip() == tribo.__file__
    # the venv was made from the current requirements and package metadata (setup.sh)
    files = b"".join(open(os.path.join(ROOT, f), "rb").read() for f in ("requirements.txt", "pyproject.toml"))
    with open(os.path.join(sys.prefix, ".requirements.sha256")) as f:
        assert f.read().strip() == hashlib.sha256(files).hexdigest()


def test_nothing_in_the_repository_changes_sys_path():
    pattern = re.compile(r"sys\.path\s*(\.\s*(insert|append|extend)|\[|\+=|=[^=])")
    tracked = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "*.py"],
                             cwd=ROOT, capture_output=True, text=True, check=True).stdout.split()
    offenders = []
    for path in tracked:
        with open(os.path.join(ROOT, path), encoding="utf-8") as f:
            for n, line in enumerate(f, 1):
                if pattern.search(line) and "pattern" not in line:
                    offenders.append(f"{path}:{n}: {line.strip()}")
    assert not offenders, offenders


# The commands users type and the functions they run: a rename here breaks scripts and docs.
# One command, tribo, with a subcommand per job; the other names are its aliases.
COMMANDS = {"tribo": "tribo.cli.main:main",
            "tribo-study": "tribo.cli.main:study", "tribo-sweep": "tribo.cli.main:sweep",
            "tribo-population": "tribo.cli.main:population",
            "tribo-impact-map": "tribo.cli.main:impact_map", "tribo-line": "tribo.cli.main:line"}
SUBCOMMANDS = ["population", "grain", "line", "impact-map", "calibrate", "sweep", "study", "dem"]
ALIASES = {"tribo-study": "study", "tribo-sweep": "sweep", "tribo-population": "population",
           "tribo-impact-map": "impact-map", "tribo-line": "line"}
# The names `import tribo` gives (README.md, docs/): changing them is a decision about the
# API, never a side effect of moving modules.
PUBLIC = ["run", "run_si", "sweep", "load_results", "find_fmu", "materials", "paschen", "population",
          "impact_map", "ImpactMap", "line_grain", "line_population", "line_mixture", "line_sweep",
          "single_impact", "repeated_impacts", "chute_stream", "calibrate"]


def test_pyproject_declares_the_console_commands():
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        assert tomllib.load(f)["project"]["scripts"] == COMMANDS


@pytest.mark.parametrize("name", COMMANDS)
def test_console_commands(name):
    scripts = {e.name: e.value for e in importlib.metadata.entry_points(group="console_scripts")}
    assert scripts[name] == COMMANDS[name]
    done = subprocess.run([command(name), "--help"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and done.stdout.startswith(f"usage: {name} ")
    if name == "tribo":
        assert all(f"    {sub} " in done.stdout or f"    {sub}\n" in done.stdout
                   for sub in SUBCOMMANDS), done.stdout
    else:  # an alias says whose, and takes the subcommand's options
        assert f"{name}: alias of `tribo {ALIASES[name]}`" in " ".join(done.stdout.split())
        assert "--scheduler" in done.stdout and "--fresh" in done.stdout


# the subcommands that run a job into an output folder (tribo grain runs one grain and
# writes nothing)
JOBS = [sub for sub in SUBCOMMANDS if sub != "grain"]


@pytest.mark.parametrize("sub", JOBS)
def test_every_job_is_a_subcommand_of_tribo(sub):
    done = subprocess.run([*subcommand(sub), "--help"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and done.stdout.startswith(f"usage: tribo {sub} ")
    assert "--scheduler" in done.stdout and "--fresh" in done.stdout and "--out FOLDER" in done.stdout
    # the aliases are the names the older commands were known by; a newer one has none
    alias = {v: k for k, v in ALIASES.items()}.get(sub)
    if alias is None:
        assert sub in ("calibrate", "dem")
        return
    helped = subprocess.run([command(alias), "--help"], capture_output=True, text=True, timeout=60)
    # the alias's options are the subcommand's
    assert helped.stdout.split("options:")[1] == done.stdout.split("options:")[1]


def test_the_public_api_is_pinned():
    assert tribo.__all__ == PUBLIC
    assert all(callable(getattr(tribo, n)) for n in PUBLIC
               if n not in ("materials", "paschen", "ImpactMap"))
    assert isinstance(tribo.ImpactMap, type) and tribo.ImpactMap.__module__.startswith("tribo.")
    assert tribo.materials.__name__ == "tribo.materials"
    # the fmpy driver the README points to, with the names the tests and examples import
    assert tribo.fmu.__name__ == "tribo.fmu"
    assert {"Instance", "FmuImage", "unpacked", "record", "model_description", "status_of",
            "OK", "WARNING", "DISCARD", "ERROR", "FATAL"} <= set(tribo.fmu.__all__)
    assert all(hasattr(tribo.fmu, n) for n in tribo.fmu.__all__)


def documents() -> dict:
    """README.md, CONTRIBUTING.md and docs/*.md: path -> text."""
    paths = [os.path.join(ROOT, "README.md"), os.path.join(ROOT, "CONTRIBUTING.md")]
    paths += sorted(glob.glob(os.path.join(ROOT, "docs", "*.md")))
    return {os.path.relpath(p, ROOT): open(p, encoding="utf-8").read() for p in paths}


def fmu_type_names() -> set:
    """The FMUs' own dotted names (enumeration types such as tribo.MotionClass)."""
    names = set()
    for xml in glob.glob(os.path.join(ROOT, "modelDescription", "*.xml")):
        names |= {t.name for t in model_description(xml).typeDefinitions}
    return names


def test_every_package_name_the_docs_use_exists():
    # tribo.x.y, not inside a path (src/chute/tribo.h) or another name (tribo_fmi3.fmu)
    pattern = re.compile(r"(?<![\w/.-])tribo(?:\.[A-Za-z_]\w*)+")
    used = {(m.group(0), where) for where, text in documents().items()
            for m in pattern.finditer(text)}
    # nor a file of the package's (an output folder's record, tribo.json)
    used = {(name, where) for name, where in used
            if name not in fmu_type_names() and not name.endswith((".json", ".csv", ".png"))}
    assert {name for name, _ in used} >= {"tribo.run", "tribo.sweep", "tribo.materials", "tribo.fmu"}
    missing = []
    for name, where in sorted(used):
        parts = name.split(".")
        obj = tribo
        for i, part in enumerate(parts[1:], 2):
            try:
                obj = getattr(obj, part) if hasattr(obj, part) else \
                    importlib.import_module(".".join(parts[:i]))
            except ImportError:
                missing.append(f"{where}: {name}")
                break
    assert not missing, missing


def test_every_package_path_the_docs_name_exists():
    paths = {(m.group(0).rstrip("."), where) for where, text in documents().items()
             for m in re.finditer(r"(?<![\w/])python/tribo(?:/[\w.*]+)*", text)}
    assert ("python/tribo/data/materials.toml", "docs/si.md") in paths
    missing = [f"{where}: {path}" for path, where in sorted(paths)
               if not glob.glob(os.path.join(ROOT, path))]
    assert not missing, missing


def test_package_data_is_part_of_the_package():
    """python/tribo/data/* (e.g. a materials table) goes with the package."""
    with open(os.path.join(ROOT, "pyproject.toml"), "rb") as f:
        project = tomllib.load(f)
    assert project["tool"]["setuptools"]["package-data"]["tribo"] == ["data/*"]
    assert project["tool"]["setuptools"]["packages"]["find"]["where"] == ["python"]


def test_run_gives_the_fmus_numbers_as_a_dataframe(fmu_file):
    params = {"epsilon": 0.3, "mu": 1.0, "nu": 1.0, "n_segments": 64}
    df = tribo.run(params, t_end=20.0, fmu=fmu_file(2))
    assert isinstance(df, pd.DataFrame) and list(df["time"]) == [float(k) for k in range(21)]
    assert {"X", "Y", "Q_static", "motion_class", "assumption_warnings"} <= set(df.columns)
    plain = simulate_fmu(fmu_file(2), stop_time=20.0, output_interval=1.0, start_values=params,
                         output=["Y", "Q_static"])
    assert np.array_equal(df["Y"].to_numpy(), plain["Y"]) and np.array_equal(df["Q_static"], plain["Q_static"])
    # the same scene as text and as keywords, and from the FMI 3.0 FMU
    text = tribo.run("epsilon=0.3 mu=1 nu=1", n_segments=64, t_end=20.0, fmu=fmu_file(3),
                     outputs=["Y", "Q_static"])
    assert list(text.columns) == ["time", "Y", "Q_static"] and text["Y"].equals(df["Y"])


def test_run_refuses_a_bad_value_with_the_fmus_reason(fmu_file):
    with pytest.raises(ParameterError, match=r"epsilon = 1.5.*0.001 <= epsilon <= 1"):
        tribo.run(epsilon=1.5, fmu=fmu_file(3))
    with pytest.raises(ValueError, match="expected name=value"):
        tribo.run("epsilon 0.5", fmu=fmu_file(3))


def test_sweep_and_load_results(fmu_file, tmp_path):
    out = str(tmp_path / "sweep")
    df = tribo.sweep({"epsilon": [0.3, 1.0], "n_segments": [64]}, t_end=20.0, out=out,
                     fmu=fmu_file(3), serial=True)
    assert list(df["epsilon"]) == [0.3, 1.0] and (df["t_end"] == 20.0).all()
    assert (tmp_path / "sweep" / "results.png").exists()
    loaded = tribo.load_results(out)  # the folder, or its file
    pd.testing.assert_frame_equal(loaded, df)
    pd.testing.assert_frame_equal(tribo.load_results(str(tmp_path / "sweep" / "results.csv")), df)
    one = tribo.run(epsilon=1.0, mu=0.1, n_segments=64, t_end=20.0, fmu=fmu_file(3))
    assert loaded["Q_static_end"].iloc[1] == one["Q_static"].iloc[-1]


@pytest.mark.parametrize("variant", VARIANTS)
@pytest.mark.parametrize("version", (2, 3))
def test_find_fmu_finds_the_built_fmu_of_the_version_and_variant(version, variant):
    md = read_model_description(tribo.find_fmu(version, variant=variant))
    assert md.fmiVersion.split(".")[0] == str(version)
    assert md.coSimulation.modelIdentifier == f"{VARIANTS[variant]}_fmi{version}"


def test_find_fmu(tmp_path, monkeypatch):
    # the checkout's build/ unless TRIBO_BUILD_DIR names another (as when testing another build)
    monkeypatch.delenv("TRIBO_BUILD_DIR", raising=False)
    assert build_dir() == os.path.join(ROOT, "build")
    monkeypatch.setenv("TRIBO_BUILD_DIR", str(tmp_path))
    assert build_dir() == str(tmp_path)
    with pytest.raises(FileNotFoundError, match="TRIBO_BUILD_DIR"):
        tribo.find_fmu(2)
    (tmp_path / "fmu").mkdir()
    (tmp_path / "fmu" / "tribo_fmi2.fmu").write_bytes(b"")
    (tmp_path / "fmu" / "tribo_fmi3.fmu").write_bytes(b"")
    assert tribo.find_fmu() == str(tmp_path / "fmu" / "tribo_fmi3.fmu")  # FMI 3.0 by default
    assert tribo.find_fmu(2) == str(tmp_path / "fmu" / "tribo_fmi2.fmu")
    assert tribo.find_fmu(str(tmp_path / "fmu" / "tribo_fmi2.fmu")) == str(tmp_path / "fmu" / "tribo_fmi2.fmu")
    (tmp_path / "fmu" / "tribo_si_fmi3.fmu").write_bytes(b"")
    assert tribo.find_fmu(variant="si") == str(tmp_path / "fmu" / "tribo_si_fmi3.fmu")
    with pytest.raises(FileNotFoundError):
        tribo.find_fmu(2, variant="si")
    with pytest.raises(ValueError, match="variant"):
        tribo.find_fmu(variant="metric")
