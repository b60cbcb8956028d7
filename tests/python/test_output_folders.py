"""Output folders (--out, out=; tribo/batch/folder.py): one command's results of one set-up
per folder, for every subcommand of `tribo` alike. Another command's or another set-up's folder is
refused in one line (nothing written), --fresh keeps what it held in backup-<n>/, a
rebuilt FMU starts the folder over saying so, and a second process on a folder in use is
locked out instead of running the same runs again."""

import json
import os
import subprocess
import time

import pandas as pd
import pytest

import tribo
from study_support import subcommand
from tribo.batch.folder import LOCK, RECORD, FolderError, claim

SHORT = ["--chute-length", "0.02", "--t-end", "1", "--serial", "--no-progress", "--no-plot"]
MAP = ["--speed", "1", "--angle-deg", "90", "--set", "n_segments=64", "--serial", "--no-progress",
       "--no-plot"]
SWEEP = ["--param", "epsilon=0.5", "--param", "n_segments=64", "--t-end", "5", "--serial",
         "--no-progress", "--no-plot"]
STUDY = ["--epsilons", "1.0", "--t-end", "5", "--transition-width", "0.5", "--serial", "--no-progress"]


def run(name, *args, timeout=300):
    return subprocess.run([*subcommand(name), *args], capture_output=True, text=True, timeout=timeout)


def one_line_error(done, name, *words):
    lines = done.stderr.strip().splitlines()
    assert done.returncode == 2 and len(lines) == 1, done.stderr
    assert lines[0].startswith(f"tribo {name}: error: ") and "Traceback" not in done.stderr
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


def test_another_set_up_is_refused_naming_what_differs_and_fresh_keeps_the_old(tmp_path):
    out = tmp_path / "pop"
    first = run("population", "-n", "3", "--seed", "1", "--out", str(out), *SHORT)
    assert first.returncode == 0, first.stderr
    before = (out / "particles.csv").read_bytes()
    # another pair and seed into the same folder: its rows would mix with the first's
    other = run("population", "-n", "3", "--seed", "2", "--particle", "PP", "--out", str(out), *SHORT)
    line = one_line_error(other, "population", f"{out} holds a population of another set-up",
                          "seed 1 -> 2", "particle PE -> PP", "--fresh")
    assert (out / "particles.csv").read_bytes() == before  # untouched
    fresh = run("population", "-n", "3", "--seed", "2", "--particle", "PP", "--out", str(out),
                "--fresh", *SHORT)
    assert fresh.returncode == 0, fresh.stderr
    assert f"the earlier results are kept in {out / 'backup-1'}" in fresh.stdout
    assert (out / "backup-1" / "particles.csv").read_bytes() == before
    rows = pd.read_csv(out / "particles.csv")
    assert len(rows) == 3 and (rows["particle"] == "PP").all() and (rows["seed"] == 2).all()
    assert json.loads((out / RECORD).read_text())["setup"]["seed"] == 2
    assert line


@pytest.mark.parametrize("name, args", [("population", ["-n", "2", *SHORT]),
                                        ("impact-map", MAP),
                                        ("study", STUDY)],
                         ids=["population", "impact map", "study"])
def test_another_commands_folder_is_refused_even_with_fresh(tmp_path, fmu_file, name, args):
    out = tmp_path / "sweep"
    done = run("sweep", *SWEEP, "--fmu", fmu_file(3), "--out", str(out))
    assert done.returncode == 0, done.stderr
    listing = sorted(os.listdir(out))
    for fresh in ([], ["--fresh"]):
        refused = run(name, *args, *fresh, "--out", str(out))
        one_line_error(refused, name, f"{out} holds the results of tribo sweep", "give another --out")
        assert sorted(os.listdir(out)) == listing


def test_files_no_tribo_command_recorded_are_refused_and_left_alone(tmp_path):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    for fresh in ([], ["--fresh"]):
        refused = run("population", "-n", "2", "--out", str(out), *SHORT, *fresh)
        one_line_error(refused, "population", "holds files that no tribo command recorded",
                       "notes.txt")
    assert sorted(os.listdir(out)) == ["notes.txt"]


def test_results_without_a_record_need_fresh_and_are_kept(tmp_path):
    out = tmp_path / "old"
    out.mkdir()
    (out / "particles.csv").write_text("key\n")
    (out / "summary.csv").write_text("")
    refused = run("population", "-n", "2", "--out", str(out), *SHORT)
    one_line_error(refused, "population", "without a record of their set-up", "--fresh")
    fresh = run("population", "-n", "2", "--out", str(out), *SHORT, "--fresh")
    assert fresh.returncode == 0, fresh.stderr
    assert sorted(os.listdir(out / "backup-1")) == ["particles.csv", "summary.csv"]


def test_a_rebuilt_fmu_starts_the_folder_over_saying_so(tmp_path):
    out = str(tmp_path / "f")
    with claim(out, "sweep", {"swept": ["epsilon"]}, "a" * 64) as first:
        assert first.backup is None
        open(os.path.join(out, "results.csv"), "w").write("key\n")
    with claim(out, "sweep", {"swept": ["epsilon"]}, "a" * 64) as same:
        assert same.backup is None and os.path.exists(os.path.join(out, "results.csv"))
    with claim(out, "sweep", {"swept": ["epsilon"]}, "b" * 64) as rebuilt:
        assert rebuilt.note == f"the FMU has changed since this folder was written: its results " \
                               f"are kept in {os.path.join(out, 'backup-1')}"
        assert not os.path.exists(os.path.join(out, "results.csv"))
        assert os.path.exists(os.path.join(out, "backup-1", "results.csv"))


def test_a_folder_in_use_is_refused_in_one_line(tmp_path):
    out = str(tmp_path / "busy")
    with claim(out, "population", {"n": 2}, "a" * 64):
        assert f"tribo population (process {os.getpid()}" in open(os.path.join(out, LOCK)).read()
        refused = run("population", "-n", "2", "--out", out, *SHORT)
        one_line_error(refused, "population", f"{out} is in use by tribo population (process "
                                                    f"{os.getpid()}", "wait for it to finish")
        with pytest.raises(FolderError, match="is in use"):
            with claim(out, "population", {"n": 2}, "a" * 64):
                pass
    with claim(out, "population", {"n": 2}, "a" * 64):  # free again once the first is done
        pass


def test_two_identical_commands_at_once_run_each_particle_once(tmp_path):
    out = tmp_path / "twice"
    cmd = [*subcommand("population"), "-n", "6", "--seed", "4", "--out", str(out), *SHORT]
    first = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline and not (out / "particles.csv").exists():
        time.sleep(0.02)
    second = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
    stdout, stderr = first.communicate(timeout=300)
    assert first.returncode == 0, stderr
    rows = pd.read_csv(out / "particles.csv")
    assert len(rows) == 6 and rows["key"].is_unique
    if second.returncode == 0:  # it started after the first had finished: nothing to run
        assert "0 run, 6 already in the file" in second.stdout
    else:
        one_line_error(second, "population", "is in use by tribo population")


@pytest.mark.parametrize("name, args", [("sweep", SWEEP), ("population", ["-n", "2", *SHORT]),
                                        ("impact-map", MAP), ("study", STUDY)],
                         ids=["sweep", "population", "impact map", "study"])
def test_out_means_a_folder_for_every_command(tmp_path, fmu_file, name, args):
    helped = run(name, "--help")
    assert "--out FOLDER" in helped.stdout and "the output folder" in helped.stdout
    a_file = tmp_path / "a_file"
    a_file.write_text("")
    extra = ["--fmu", fmu_file(3)] if name in ("sweep", "study") else []
    refused = run(name, *args, *extra, "--out", str(a_file))
    one_line_error(refused, name, f"{a_file}", "not a folder")
    nested = tmp_path / "new" / "dir" / "out"
    done = run(name, *args, *extra, "--out", str(nested))
    assert done.returncode == 0, done.stderr
    assert nested.is_dir() and (nested / RECORD).is_file()


def test_the_api_keeps_to_the_same_folders(tmp_path):
    out = str(tmp_path / "api")
    tribo.population(2, seed=1, chute={"chute_length": 0.02}, t_end=1.0, out=out, serial=True)
    with pytest.raises(FolderError, match=r"holds a population of another set-up \(seed 1 -> 2"):
        tribo.population(2, seed=2, chute={"chute_length": 0.02}, t_end=1.0, out=out, serial=True)
    with pytest.raises(FolderError, match="holds the results of tribo population"):
        tribo.sweep({"epsilon": [0.5], "n_segments": [64]}, t_end=5.0, out=out, serial=True)
