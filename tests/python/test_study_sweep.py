"""Sweeps (examples/tribo_study/sweep.py, executors.py, results.py; examples/sweep.py):
Dask gives the serial run's numbers, an interrupted or limited sweep resumes without
redoing finished runs and ends with the uninterrupted sweep's file, and a sweep runs on
an existing Dask cluster that does not have the package."""

import os
import socket
import subprocess
import sys
import time

import pandas as pd
import pytest

from study_support import EXAMPLES, PYTHON, CountingRun, image_of, short_spec, without_timing
from tribo_study.fmu_run import run_fmu
from tribo_study.executors import DaskExecutor, SerialExecutor
from tribo_study.results import read_results
from tribo_study.specs import run_key
from tribo_study.sweep import run_sweep, series_path

sys.path.insert(0, EXAMPLES)
import sweep as sweep_cli  # noqa: E402  (examples/sweep.py)

SPECS = [short_spec(e, f, t_end=100.0) for f in ("low", "high") for e in (0.3, 0.6, 1.0)]


@pytest.fixture(scope="module")
def image(fmu_file):
    return image_of(fmu_file)


@pytest.fixture(scope="module")
def local_dask():
    """One embedded local cluster (2 worker processes) for the module."""
    with DaskExecutor(workers=2) as executor:
        yield executor


@pytest.fixture(scope="module")
def uninterrupted(image, tmp_path_factory):
    """The reference: the sweep run serially in one go."""
    path = str(tmp_path_factory.mktemp("reference") / "results.csv")
    with SerialExecutor() as ex:
        report = run_sweep(SPECS, image, path, ex, progress=False)
    assert report.executed == len(SPECS) and report.complete
    return read_results(path)


def test_dask_local_cluster_equals_serial(image, local_dask, uninterrupted, tmp_path):
    assert local_dask.workers == 2
    path = str(tmp_path / "results.csv")
    report = run_sweep(SPECS, image, path, local_dask, series_dir=str(tmp_path / "series"),
                       progress=False)
    assert report.executed == len(SPECS) and not report.failed
    result = read_results(path)
    pd.testing.assert_frame_equal(without_timing(result), without_timing(uninterrupted))
    assert (result["cpu_s"] > 0).all()
    # the series written from the workers' results are the serial run's series
    key = run_key(SPECS[-1], image.sha256)
    serial = run_fmu(image, SPECS[-1])
    on_disk = pd.read_csv(series_path(str(tmp_path / "series"), key))
    assert on_disk["Y"].to_numpy() == pytest.approx(serial.series["Y"].to_numpy(), rel=1e-9)


def test_results_load_with_plain_pandas(uninterrupted, image, tmp_path):
    path = str(tmp_path / "results.csv")
    with SerialExecutor() as ex:
        run_sweep(SPECS[:2], image, path, ex, progress=False)
    plain = pd.read_csv(path)
    assert list(plain["epsilon"]) == [0.3, 0.6] and list(plain["mu"]) == [0.1, 0.1]
    assert plain["turned_over"].dtype.kind == "i"
    # the numbers read back are the run's, bit for bit
    direct = run_fmu(image, SPECS[1]).row
    for column in ("Q_static_t100", "Q_sliding_t40", "contact_fraction", "turns", "Y_max"):
        assert plain[column].iloc[1] == direct[column], column


def test_limited_sweep_resumes_without_redoing_runs(image, uninterrupted, tmp_path):
    path = str(tmp_path / "results.csv")
    first, second = CountingRun(), CountingRun()
    with SerialExecutor() as ex:
        r1 = run_sweep(SPECS, image, path, ex, max_runs=2, progress=False, run=first)
        assert (r1.executed, r1.skipped, len(r1.results), r1.complete) == (2, 0, 2, False)
        assert len(read_results(path)) == 2
        r2 = run_sweep(SPECS, image, path, ex, progress=False, run=second)
    assert len(first.specs) == 2 and len(second.specs) == len(SPECS) - 2
    assert (r2.executed, r2.skipped) == (len(SPECS) - 2, 2)
    assert not {s.as_json() for s in first.specs} & {s.as_json() for s in second.specs}
    pd.testing.assert_frame_equal(without_timing(read_results(path)), without_timing(uninterrupted))


def test_interrupted_sweep_resumes(image, uninterrupted, tmp_path):
    """Ctrl-C after three runs, then a row cut short by the interruption: the resumed sweep
    runs only what is missing and ends with the uninterrupted sweep's file."""
    path, series = str(tmp_path / "results.csv"), str(tmp_path / "series")
    interrupted = CountingRun(interrupt_after=3)
    with SerialExecutor() as ex, pytest.raises(KeyboardInterrupt):
        run_sweep(SPECS, image, path, ex, series_dir=series, progress=False, run=interrupted)
    assert len(read_results(path)) == 3
    with open(path, "a") as f:
        f.write("0123456789abcdef,0.001,45.0,1.0")  # a row cut short, no newline
    resumed = CountingRun()
    with SerialExecutor() as ex:
        report = run_sweep(SPECS, image, path, ex, series_dir=series, progress=False, run=resumed)
    assert len(resumed.specs) == len(SPECS) - 3 and report.complete
    assert {s.as_json() for s in resumed.specs} == {s.as_json() for s in SPECS[3:]}
    pd.testing.assert_frame_equal(without_timing(read_results(path)), without_timing(uninterrupted))

    # a run whose series went missing is run again; the others are not
    os.remove(series_path(series, run_key(SPECS[1], image.sha256)))
    again = CountingRun()
    with SerialExecutor() as ex:
        run_sweep(SPECS, image, path, ex, series_dir=series, progress=False, run=again)
    assert [s.as_json() for s in again.specs] == [SPECS[1].as_json()]

    # --fresh: everything again
    fresh = CountingRun()
    with SerialExecutor() as ex:
        run_sweep(SPECS, image, path, ex, resume=False, progress=False, run=fresh)
    assert len(fresh.specs) == len(SPECS)


def test_a_file_of_other_runs_is_not_mixed_in(image, tmp_path):
    path = str(tmp_path / "results.csv")
    with SerialExecutor() as ex:
        run_sweep(SPECS[:1], image, path, ex, progress=False)
        with pytest.raises(ValueError, match="other runs"):  # another horizon: other columns
            run_sweep([short_spec(0.3, "low", t_end=50.0)], image, path, ex, progress=False)


def test_the_key_is_stable_and_specific(image):
    a = short_spec(0.3, "low")
    assert run_key(a, image.sha256) == run_key(short_spec(0.1 + 0.2, "low"), image.sha256)
    assert run_key(a, image.sha256) != run_key(short_spec(0.3, "low", eta=0.2), image.sha256)
    assert run_key(a, image.sha256) != run_key(a, "another FMU")


def test_sweep_cli_builds_the_grid(fmu_file):
    kinds = sweep_cli.parameter_kinds(fmu_file(2))
    swept = [sweep_cli.parse_param("epsilon=0.1:1.0:10"), sweep_cli.parse_param("mu=0.1,1.0"),
             sweep_cli.parse_param("n_segments=64")]
    specs = sweep_cli.build_specs(swept, sweep_cli.PAPER_BASE, kinds, 500, 1.0)
    assert len(specs) == 20
    assert [s.params["epsilon"] for s in specs[::2]] == [round(0.1 * k, 12) for k in range(1, 11)]
    assert all(s.params["nu"] == s.params["mu"] for s in specs)  # nu follows mu
    assert all(type(s.params["n_segments"]) is int for s in specs)
    untied = sweep_cli.build_specs(swept[1:2], sweep_cli.PAPER_BASE, kinds, 500, 1.0, tie=False)
    assert [s.params["nu"] for s in untied] == [0.1, 0.1]
    with pytest.raises(SystemExit, match="not parameters"):
        sweep_cli.build_specs([("roundness", [0.5])], {}, kinds, 500, 1.0)


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def external_cluster(tmp_path):
    """A Dask scheduler and two workers started from the command line, in a directory and
    environment where the study package cannot be imported."""
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    dask = os.path.join(os.path.dirname(PYTHON), "dask")
    procs = [subprocess.Popen([dask, "scheduler", "--host", "127.0.0.1", "--port", str(port),
                               "--no-dashboard"], cwd=tmp_path, env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    procs.append(subprocess.Popen([dask, "worker", address, "--nworkers", "2", "--nthreads", "1",
                                   "--no-dashboard"], cwd=tmp_path, env=env,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    try:
        yield address
    finally:
        from distributed import Client
        try:  # a clean shutdown of scheduler and workers is quicker than signals to each
            with Client(address, timeout=5) as c:
                c.shutdown()
        except Exception:
            for p in reversed(procs):
                p.terminate()
        for p in procs:
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                p.kill()


def test_sweep_on_an_existing_cluster(image, uninterrupted, external_cluster, tmp_path):
    from distributed import Client

    with Client(external_cluster, timeout=30) as c:
        c.wait_for_workers(2, timeout=30)
        # the package is not importable there before the sweep sends it
        assert not any(c.run(lambda: __import__("importlib").util.find_spec("tribo_study")
                             is not None).values())
    path = str(tmp_path / "results.csv")
    with DaskExecutor(address=external_cluster) as executor:
        report = run_sweep(SPECS, image, path, executor, progress=False)
        where = executor.client.run(lambda: __import__("tribo_study").__file__)
    assert report.executed == len(SPECS) and not report.failed
    assert all(".zip" in f for f in where.values())  # the uploaded package
    pd.testing.assert_frame_equal(without_timing(read_results(path)), without_timing(uninterrupted))


def test_sweep_cli_runs_and_resumes(fmu_file, tmp_path):
    out = tmp_path / "results.csv"
    cmd = [PYTHON, os.path.join(EXAMPLES, "sweep.py"), "--param", "epsilon=0.4,1.0",
           "--param", "mu=0.1,1.0", "--param", "n_segments=64", "--t-end", "60", "--out", str(out),
           "--fmu", fmu_file(2), "--serial", "--no-progress"]
    first = subprocess.run(cmd + ["--max-runs", "3"], capture_output=True, text=True, check=True)
    assert "3 executed, 0 already in the file" in first.stdout
    second = subprocess.run(cmd, capture_output=True, text=True, check=True)
    assert "1 executed, 3 already in the file, 0 failed; 4 of 4 runs done" in second.stdout
    df = pd.read_csv(out)
    assert sorted(zip(df["epsilon"], df["mu"])) == [(0.4, 0.1), (0.4, 1.0), (1.0, 0.1), (1.0, 1.0)]
    assert (df["nu"] == df["mu"]).all()
