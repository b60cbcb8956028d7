"""Sweeps (tribo/batch/: sweep.py, executors.py, results.py, grid.py; tribo sweep): Dask
gives the serial run's numbers, an interrupted or limited sweep resumes without redoing
finished runs and ends with the uninterrupted sweep's file, runs of different horizons
share a file, a fresh start keeps the old file, and a sweep runs on an existing Dask
cluster that does not have the package."""

import os
import signal
import socket
import subprocess
import sys
import time

import numpy as np
import pandas as pd
import pytest

from study_support import PYTHON, CountingRun, image_of, short_spec, subcommand, without_timing
from tribo.batch.executors import DaskExecutor, SerialExecutor
from tribo.batch.grid import PAPER_BASE, build_specs, parse_param
from tribo.batch.particle import run_fmu
from tribo.batch.results import csv_line, read_results
from tribo.batch.specs import run_key
from tribo.batch.sweep import run_sweep, series_path
from tribo.fmu.parameters import ParameterError, check_names, integer_names

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


def test_the_local_cluster_keeps_no_dashboards_profile_and_looks_at_itself_seldom(local_dask):
    """The local cluster serves no dashboard: its workers sample no profile for one, and its
    servers look at their event loop and memory once a second, not 50 and 10 times
    (executors.LOCAL_CLUSTER_CONFIG), in every run of it."""
    def callbacks(dask_worker):
        return {name: pc.callback_time for name, pc in dask_worker.periodic_callbacks.items()}

    for found in local_dask.client.run(callbacks).values():
        assert "profile" not in found and "profile-cycle" not in found
        assert found["tick"] == 1000 and found["memory_monitor"] == 1000


def test_results_load_with_plain_pandas(uninterrupted, image, tmp_path):
    path = str(tmp_path / "results.csv")
    with SerialExecutor() as ex:
        run_sweep(SPECS[:2], image, path, ex, progress=False)
    plain = pd.read_csv(path)
    assert list(plain["epsilon"]) == [0.3, 0.6] and list(plain["mu"]) == [0.1, 0.1]
    assert plain["turned_over"].dtype.kind == "i"
    # the numbers read back are the run's, bit for bit
    direct = run_fmu(image, SPECS[1]).row
    for column in ("Q_static_end", "Q_sliding_40pct", "contact_fraction", "turns", "Y_max"):
        assert plain[column].iloc[1] == direct[column], column


def test_a_row_is_written_as_pandas_writes_it():
    """results.csv_line against a one-row DataFrame's to_csv (what the file's rows were):
    floats of every size and sign, the non-finite ones, numpy's scalars, integers, booleans,
    text that needs quoting, nothing."""
    rng = np.random.default_rng(3)
    floats = list(rng.standard_normal(2000) * 10.0 ** rng.integers(-300, 300, 2000))
    values = floats + [0.1, 1e16, 1e15, 9.999999999999999e15, 1e-5, 5e-324, -0.0, 0.0, np.inf,
                       -np.inf, np.nan, np.float64(0.3), np.int64(-7), 3, 2**63 - 1, True,
                       np.bool_(False), "PE", "a,b", 'say "x"', "two\nlines", "", None]
    for k in range(0, len(values), 50):
        row = ["key"] + values[k:k + 50]
        expected = pd.DataFrame([dict(enumerate(row))]).to_csv(header=False, index=False)
        assert csv_line(row) == expected


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


def test_ctrl_c_during_a_serial_run_is_held_until_the_run_is_handed_over():
    """SIGINT in the middle of a run (where the FMU may be calling its logger, a ctypes
    callback that would drop the KeyboardInterrupt): the run finishes, its result is
    yielded, then the interruption is raised; the next run does not start."""
    started = []

    def run(image, spec):
        started.append(spec)
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(0.05)  # the signal is delivered inside the run
        return f"result {spec}"

    got = []
    with SerialExecutor() as ex, pytest.raises(KeyboardInterrupt):
        for outcome in ex.run(run, None, [1, 2, 3]):
            got.append(outcome)
    assert got == [(0, "result 1")] and started == [1]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


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


def test_runs_of_other_horizons_share_the_file(image, tmp_path):
    """A longer horizon into the same file adds its rows; both sweeps' rows stay, and each
    is the run of its own horizon."""
    path = str(tmp_path / "results.csv")
    longer = [short_spec(e, "low", t_end=150.0) for e in (0.3, 0.6)]
    with SerialExecutor() as ex:
        first = run_sweep(SPECS[:2], image, path, ex, progress=False)
        second = run_sweep(longer, image, path, ex, progress=False)
    assert first.executed == 2 and second.executed == 2 and second.skipped == 0
    table = read_results(path)
    assert len(table) == 4 and sorted(table["t_end"]) == [100.0, 100.0, 150.0, 150.0]
    assert set(table["key"]) == set(first.keys) | set(second.keys)
    assert table.set_index("key").loc[second.keys[1], "Q_static_end"] == run_fmu(image, longer[1]).row["Q_static_end"]


def test_a_file_of_other_parameters_is_refused_saying_which(image, tmp_path):
    path = str(tmp_path / "results.csv")
    with SerialExecutor() as ex:
        run_sweep(SPECS[:1], image, path, ex, progress=False)
        with pytest.raises(ValueError, match=r"other columns \(these runs have phi0_deg\).*--fresh"):
            run_sweep([short_spec(0.3, "low", t_end=100.0, phi0_deg=5.0)], image, path, ex, progress=False)
    assert len(read_results(path)) == 1  # untouched


def test_a_fresh_start_keeps_the_old_file(image, tmp_path):
    path = tmp_path / "results.csv"
    with SerialExecutor() as ex:
        run_sweep(SPECS[:2], image, str(path), ex, progress=False)
        before = path.read_bytes()
        report = run_sweep(SPECS[:1], image, str(path), ex, resume=False, progress=False)
        assert report.backup == str(tmp_path / "results.backup-1.csv")
        again = run_sweep(SPECS[:1], image, str(path), ex, resume=False, progress=False)
    assert (tmp_path / "results.backup-1.csv").read_bytes() == before  # the 2 rows, kept
    assert again.backup == str(tmp_path / "results.backup-2.csv")
    assert len(read_results(str(path))) == 1


def test_the_key_is_stable_and_specific(image):
    a = short_spec(0.3, "low")
    assert run_key(a, image.sha256) == run_key(short_spec(0.1 + 0.2, "low"), image.sha256)
    assert run_key(a, image.sha256) != run_key(short_spec(0.3, "low", eta=0.2), image.sha256)
    assert run_key(a, image.sha256) != run_key(a, "another FMU")


def test_the_grid_of_a_sweep(image):
    md = image.model_description()
    swept = [parse_param("epsilon=0.1:1.0:10"), parse_param("mu=0.1,1.0"), parse_param("n_segments=64")]
    specs = build_specs(swept, PAPER_BASE, integer_names(md), 500, 1.0)
    assert len(specs) == 20
    assert [s.params["epsilon"] for s in specs[::2]] == [round(0.1 * k, 12) for k in range(1, 11)]
    assert all(s.params["nu"] == s.params["mu"] for s in specs)  # nu follows mu
    assert all(type(s.params["n_segments"]) is int for s in specs)
    assert "rtol" not in specs[0].params  # the FMU's default tolerances
    untied = build_specs(swept[1:2], PAPER_BASE, integer_names(md), 500, 1.0, tie=False)
    assert [s.params["nu"] for s in untied] == [0.1, 0.1]
    with pytest.raises(ParameterError, match="not parameters"):
        check_names(md, ["roundness"])
    with pytest.raises(ValueError, match="n_segments = 100.5 is not a whole number"):
        build_specs([("n_segments", [100.5])], {}, integer_names(md), 500, 1.0)


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture
def external_cluster(tmp_path):
    """A Dask scheduler and two workers started from the command line with the README's
    flags that keep them on the loopback interface (without --dashboard-address, each
    listens on 0.0.0.0 for HTTP even with --no-dashboard), the workers where the package cannot
    be imported: the venv's site-packages on their path without its .pth files (python -S),
    so without the editable install's entry."""
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    site_packages = next(p for p in sys.path if p.endswith("site-packages") and p.startswith(sys.prefix))
    env = dict({k: v for k, v in os.environ.items() if k != "PYTHONPATH"})
    procs = [subprocess.Popen([PYTHON, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                               "--port", str(port), "--dashboard-address", "127.0.0.1:0", "--no-dashboard"],
                              cwd=tmp_path, env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    procs.append(subprocess.Popen([PYTHON, "-S", "-m", "distributed.cli.dask_worker", address,
                                   "--host", "127.0.0.1", "--dashboard-address", "127.0.0.1:0", "--no-dashboard",
                                   "--nworkers", "2", "--nthreads", "1"], cwd=tmp_path,
                                  env=dict(env, PYTHONPATH=site_packages),
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    try:
        yield address, procs
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

    address, procs = external_cluster
    with Client(address, timeout=30) as c:
        c.wait_for_workers(2, timeout=30)
        # the package is not importable there before the sweep sends it
        assert not any(c.run(lambda: __import__("importlib").util.find_spec("tribo")
                             is not None).values())
    path = str(tmp_path / "results.csv")
    with DaskExecutor(address=address) as executor:
        report = run_sweep(SPECS, image, path, executor, progress=False)
        where = executor.client.run(lambda: __import__("tribo").__file__)
    assert report.executed == len(SPECS) and not report.failed
    assert all(".zip" in f for f in where.values())  # the uploaded package
    pd.testing.assert_frame_equal(without_timing(read_results(path)), without_timing(uninterrupted))
    # the README's flags keep the cluster on the loopback interface
    assert listening_addresses(procs) and all(ip == "127.0.0.1" for ip in listening_addresses(procs))


def listening_addresses(procs) -> list[str]:
    """The IP addresses on which the processes (and their children) listen."""
    import psutil
    ips = []
    for p in procs:
        tree = psutil.Process(p.pid)
        for q in [tree] + tree.children(recursive=True):
            ips += [c.laddr.ip for c in q.net_connections(kind="inet") if c.status == psutil.CONN_LISTEN]
    return ips


def test_sweep_cli_runs_and_resumes(fmu_file, tmp_path):
    out = tmp_path / "results.csv"
    cmd = [*subcommand("sweep"), "--param", "epsilon=0.4,1.0",
           "--param", "mu=0.1,1.0", "--param", "n_segments=64", "--t-end", "60", "--out", str(tmp_path),
           "--fmu", fmu_file(2), "--serial", "--no-progress", "--no-plot"]
    first = subprocess.run(cmd + ["--max-runs", "3"], capture_output=True, text=True, check=True)
    assert "3 executed, 0 already in the file" in first.stdout
    second = subprocess.run(cmd, capture_output=True, text=True, check=True)
    assert "1 executed, 3 already in the file, 0 failed; 4 of 4 runs done" in second.stdout
    df = pd.read_csv(out)
    assert sorted(zip(df["epsilon"], df["mu"])) == [(0.4, 0.1), (0.4, 1.0), (1.0, 0.1), (1.0, 1.0)]
    assert (df["nu"] == df["mu"]).all()
