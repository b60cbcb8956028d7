"""Bad input to `tribo` and its subcommands, and to the package's functions, as a user
meets it: every mistake is one line on stderr (no traceback) and a non-zero exit, before
anything runs or any memory is taken for it; a results file that does not read back as
written is never kept as results (its rows run again); the documented benchmark runs on a
fresh clone.

The commands run in a process whose address space is limited (LIMIT_BYTES): a size that
were taken for real would fail there at once instead of filling the machine's memory."""

import os
import resource
import shutil
import subprocess
import zipfile

import pandas as pd
import pytest

import tribo
from study_support import BIN, subcommand
from tribo.batch import job as batch_job
from tribo.batch.folder import LOCK, FolderError, claim
from tribo.batch.specs import MAX_RUNS
from tribo_fmu import ROOT

LIMIT_BYTES = 4 << 30
SHORT = ["--chute-length", "0.02", "--t-end", "1", "--serial", "--no-progress", "--no-plot"]


def limited():
    resource.setrlimit(resource.RLIMIT_AS, (LIMIT_BYTES, LIMIT_BYTES))


def run(sub, *args, cwd=None, timeout=300):
    return subprocess.run([*subcommand(sub), *args], capture_output=True, text=True, cwd=cwd,
                          timeout=timeout, preexec_fn=limited)


def one_line_error(done, sub, *words):
    lines = done.stderr.strip().splitlines()
    assert done.returncode == 2 and len(lines) == 1, done.stderr[-3000:]
    assert lines[0].startswith(f"tribo {sub}: error: ") and "Traceback" not in done.stderr
    for w in words:
        assert w in lines[0], (w, lines[0])
    return lines[0]


@pytest.mark.parametrize("sub, args, says", [
    ("population", ["-n", "100000000000"], f"100000000000 is more than the {MAX_RUNS}"),
    ("line", ["sweep", "--voltages", "1:2:1000000000"], f"1000000000 is more than the {MAX_RUNS}"),
    ("impact-map", ["--speed", "0:1:100000000", "--angle-deg", "90"],
     f"100000000 is more than the {MAX_RUNS}"),
    ("sweep", ["--param", "epsilon=0.1:1:100000", "--param", "mu=0.1:1:100000", "--t-end", "10"],
     f"10000000000 is more than the {MAX_RUNS}"),
    ("impact-map", ["--speed", "0.1:1:1000", "--angle-deg", "1:90:1000", "--epsilon", "0.1:1:10"],
     f"10000000 is more than the {MAX_RUNS}"),
], ids=["particles", "voltages", "speeds", "sweep grid", "map grid"])
def test_a_size_beyond_the_bound_is_one_line_naming_it(tmp_path, sub, args, says):
    done = run(sub, *args, "--out", str(tmp_path / "o"), "--serial")
    one_line_error(done, sub, says)
    assert not (tmp_path / "o").exists()


def test_the_api_refuses_a_size_beyond_the_bound(tmp_path):
    with pytest.raises(ValueError, match=f"100000000000 is more than the {MAX_RUNS}"):
        tribo.population(10**11, out=str(tmp_path / "p"), serial=True)


@pytest.mark.parametrize("sub, args", [
    ("population", ["-n", "2"]), ("impact-map", ["--speed", "1", "--angle-deg", "90"]),
    ("sweep", ["--param", "epsilon=0.5", "--t-end", "5"]), ("line", ["mixture", "-n", "2"]),
    ("study", ["--epsilons", "1.0", "--t-end", "5"]),
])
def test_a_file_that_is_not_an_fmu_is_one_line(tmp_path, sub, args):
    junk = tmp_path / "junk.fmu"
    junk.write_bytes(b"this is not a zip archive\n")
    done = run(sub, *args, "--fmu", str(junk), "--out", str(tmp_path / "o"), "--serial")
    one_line_error(done, sub, f"{junk}: not an FMU (not a zip archive)")


@pytest.mark.parametrize("members, says", [
    ({"readme.txt": "no description"}, "no modelDescription.xml in the archive"),
    ({"modelDescription.xml": "<fmiModelDescription"}, "its modelDescription.xml: "),
], ids=["no description", "not XML"])
def test_an_archive_that_is_not_an_fmu_is_one_line(tmp_path, members, says):
    fake = tmp_path / "fake.fmu"
    with zipfile.ZipFile(fake, "w") as z:
        for name, text in members.items():
            z.writestr(name, text)
    done = run("population", "-n", "2", "--fmu", str(fake), "--out", str(tmp_path / "o"))
    one_line_error(done, "population", f"{fake}: not an FMU ({says}")
    with pytest.raises(ValueError, match="not an FMU"):
        tribo.population(2, fmu=str(fake), out=str(tmp_path / "api"), serial=True)


@pytest.fixture
def population(tmp_path):
    """A finished 3-particle population's folder, its command line and rows."""
    out = tmp_path / "p"
    argv = ["-n", "3", "--seed", "5", "--out", str(out), *SHORT]
    done = run("population", *argv)
    assert done.returncode == 0, done.stderr
    return out, argv, pd.read_csv(out / "particles.csv")


def test_a_results_file_of_other_columns_is_one_line(population):
    out, argv, _ = population
    path = out / "particles.csv"
    text = path.read_text()
    path.write_text(text.replace("exit_time", "exit_t", 1))
    one_line_error(run("population", *argv), "population", f"{path} holds runs with other columns",
                   "the file has exit_t", "--fresh")


def test_junk_appended_to_a_results_file_is_left_out_and_the_runs_are_kept(population):
    out, argv, rows = population
    path = out / "particles.csv"
    with open(path, "ab") as f:
        f.write(b"\xff\xfe\x00 not text\n\x80\x81,2,3\nalso,not,a,row\n\x9c")
    again = run("population", *argv)
    assert again.returncode == 0 and "Traceback" not in again.stderr, again.stderr
    assert "0 run, 3 already in the file" in again.stdout
    assert "3 row(s) that do not read back" in again.stdout  # the cut-short last one: dropped
    pd.testing.assert_frame_equal(pd.read_csv(path), rows)
    assert (out / "particles.backup-1.csv").read_bytes().endswith(b"also,not,a,row\n\x9c")


def test_a_garbled_row_is_run_again_not_kept(population):
    out, argv, rows = population
    path = out / "particles.csv"
    lines = path.read_text().splitlines(keepends=True)
    column = lines[0].split(",").index("charge_to_mass_static")
    fields = lines[2].split(",")
    fields[column] = "x.y01"
    lines[2] = ",".join(fields)
    path.write_text("".join(lines))
    again = run("population", *argv)
    assert again.returncode == 0 and "Traceback" not in again.stderr, again.stderr
    assert "1 run, 2 already in the file" in again.stdout
    assert "x.y01" not in path.read_text()
    # the particle run again gives its number back, bit for bit
    pd.testing.assert_frame_equal(pd.read_csv(path).drop(columns=["cpu_s", "wall_s"]),
                                  rows.drop(columns=["cpu_s", "wall_s"]))


def test_an_unwritable_output_folder_is_one_clear_error_from_the_api(tmp_path, monkeypatch):
    """Files cannot be made in the folder (a read-only folder, for anyone but root): the API
    raises one OSError naming the folder, before anything runs."""
    out = tmp_path / "read-only"
    out.mkdir()

    def refused(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(batch_job.tempfile, "NamedTemporaryFile", refused)
    with pytest.raises(OSError, match=f"^cannot write into {out}: Permission denied$"):
        tribo.population(2, out=str(out), serial=True, chute={"chute_length": 0.02}, t_end=1.0)
    assert os.listdir(out) == []


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into a read-only folder")
def test_a_read_only_output_folder_is_one_clear_error_from_the_api(tmp_path):
    out = tmp_path / "read-only"
    out.mkdir()
    out.chmod(0o555)
    try:
        with pytest.raises(OSError, match=f"cannot write into {out}"):
            tribo.population(2, out=str(out), serial=True, chute={"chute_length": 0.02}, t_end=1.0)
    finally:
        out.chmod(0o755)


def test_a_lock_that_cannot_be_opened_is_a_folder_error(tmp_path):
    out = tmp_path / "o"
    (out / LOCK).mkdir(parents=True)  # not a file: open() fails as on a read-only folder
    with pytest.raises(FolderError, match=f"^cannot write into {out}: "):
        with claim(str(out), "population", {}, "0" * 64):
            pass


@pytest.mark.parametrize("sub, args, typed", [
    ("population", ["-n", "2", "--tilt", "0.5"], "--tilt 0.5"),
    ("line", ["grain", "--tilt", "0.5"], "--tilt 0.5"),
    ("impact-map", ["--speed", "1", "--angle-deg", "90", "--phi0", "0"], "--phi0 0"),
    ("sweep", ["--param", "epsilon=0.5", "--t", "5"], "--t 5"),
    ("study", ["--eps", "0.5"], "--eps 0.5"),
])
def test_an_option_is_taken_by_its_full_name_only(tmp_path, sub, args, typed):
    done = run(sub, *args, "--out", str(tmp_path / "o"))
    line = one_line_error(done, sub, f"unrecognized arguments: {typed}")
    assert line.endswith("(see --help)")
    alias = subprocess.run([os.path.join(BIN, f"tribo-{sub}"), *args, "--out", str(tmp_path / "o")],
                           capture_output=True, text=True, timeout=120)
    assert alias.returncode == 2 and f"unrecognized arguments: {typed}" in alias.stderr


@pytest.mark.parametrize("sub, args, says", [
    ("line", ["grain", "--size", "-1e-3"], "size = -0.001 is invalid"),
    ("population", ["-n", "2", "--size", "-1e-3"], "size = -0.001 is invalid"),
    ("population", ["-n", "2", "--chute-length", "-3e-1"], "chute_length = -0.3 is invalid"),
    ("impact-map", ["--speed", "-1e0", "--angle-deg", "90"], "speed = -1"),
    ("sweep", ["--param", "epsilon=0.5", "--t-end", "-1e1"], "t_end must be a positive number"),
])
def test_a_negative_number_is_a_value_whose_check_answers(tmp_path, sub, args, says):
    one_line_error(run(sub, *args, "--out", str(tmp_path / "o"), "--serial"), sub, says)


def test_the_population_benchmark_runs_on_a_fresh_clone(tmp_path):
    """scripts/bench_population.sh as a fresh clone has it: no out/ folder yet."""
    clone = tmp_path / "clone"
    (clone / "scripts").mkdir(parents=True)
    shutil.copy(os.path.join(ROOT, "scripts", "bench_population.sh"), clone / "scripts")
    (clone / ".venv").symlink_to(os.path.dirname(BIN))
    env = dict(os.environ, TRIBO_POPULATION_OPTIONS="--chute-length 0.02 --t-end 1")
    done = subprocess.run([str(clone / "scripts" / "bench_population.sh"), "2", "1"], cwd=clone,
                          capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "1 worker(s): 2 of 2 particles" in done.stdout
    assert (clone / "out" / "bench_population" / "workers-1.log").is_file()
