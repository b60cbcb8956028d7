"""tribo sweep as a new user tries it: a scheduler that does not answer, an HTTP server or
a scheduler without workers at the address, or an address without a scheme or port; bad
values and horizons; unwritable outputs; Ctrl-C; a longer horizon into the same folder;
--fresh; the embedded cluster's network exposure; the figure. Each mistake is one line on
stderr, within the connect timeout, before any run is made."""

import math
import os
import signal
import socket
import subprocess
import sys
import time
import urllib.error
import urllib.request

import pandas as pd
import psutil
import pytest

from figure_checks import assert_legends_cover_no_data

from study_support import command, subcommand
from tribo.batch.executors import DaskExecutor, scheduler_address
from tribo.batch.specs import DECIMALS

SMALL = ["--param", "n_segments=64", "--no-progress"]


def sweep(*args, timeout=120):
    started = time.perf_counter()
    done = subprocess.run([*subcommand("sweep"), *args], capture_output=True, text=True,
                          timeout=timeout)
    return done, time.perf_counter() - started


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def assert_one_line_error(done, *words):
    assert done.returncode == 2, done
    lines = done.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("tribo sweep: error: "), done.stderr
    assert "Traceback" not in done.stderr and "sweep:" not in done.stdout  # nothing started
    for w in words:
        assert w in lines[0], (w, lines[0])


def test_scheduler_addresses_without_scheme_or_port_are_understood():
    assert scheduler_address("localhost") == "tcp://localhost:8786"
    assert scheduler_address("localhost:9000") == "tcp://localhost:9000"
    assert scheduler_address("tcp://10.1.2.3") == "tcp://10.1.2.3:8786"
    assert scheduler_address("tls://host:8786") == "tls://host:8786"
    assert scheduler_address("[::1]:8800") == "tcp://[::1]:8800"
    for bad, why in (("localhost:port", "port must be a number"), ("http://h:1", "unknown protocol"),
                     ("tcp://", "expected"), ("h:99999", "port must be a number")):
        with pytest.raises(ValueError, match=why):
            scheduler_address(bad)


def test_a_scheduler_that_does_not_answer_is_one_line_within_seconds(fmu_file, tmp_path):
    port = free_port()  # nothing listens there
    done, elapsed = sweep("--param", "epsilon=0.5", *SMALL, "--t-end", "10", "--fmu", fmu_file(3),
                          "--out", str(tmp_path / "r"), "--scheduler", f"localhost:{port}",
                          "--connect-timeout", "2")
    assert_one_line_error(done, f"no Dask scheduler answered at tcp://localhost:{port} within 2 s")
    assert elapsed < 60  # a hang guard: the message says which wait was taken
    assert not (tmp_path / "r" / "results.csv").exists()


@pytest.fixture
def http_server():
    """An HTTP server on a free port of 127.0.0.1 (as a Dask dashboard is): it takes a
    connection and waits for a request."""
    port = free_port()
    p = subprocess.Popen([sys.executable, "-m", "http.server", str(port), "--bind", "127.0.0.1"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                time.sleep(0.1)
        yield port
    finally:
        p.terminate()
        p.wait(timeout=10)


def test_an_http_server_at_the_address_is_one_line_within_the_timeout(fmu_file, tmp_path, http_server):
    done, elapsed = sweep("--param", "epsilon=0.5", *SMALL, "--t-end", "10", "--fmu", fmu_file(3),
                          "--out", str(tmp_path / "r"), "--scheduler", f"127.0.0.1:{http_server}",
                          "--connect-timeout", "2", timeout=60)
    assert_one_line_error(done, f"tcp://127.0.0.1:{http_server} is not a Dask scheduler",
                          "said nothing within 2 s")
    assert elapsed < 60  # a hang guard: Dask's client alone waited for ever (killed after minutes)


@pytest.fixture
def scheduler_without_workers():
    port = free_port()
    p = subprocess.Popen([command("dask"), "scheduler", "--host", "127.0.0.1", "--port", str(port),
                          "--dashboard-address", "127.0.0.1:0", "--no-dashboard"],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                time.sleep(0.2)
        yield port
    finally:
        p.terminate()
        p.wait(timeout=20)


def test_a_scheduler_without_workers_is_one_line_within_the_timeout(fmu_file, tmp_path,
                                                                     scheduler_without_workers):
    port = scheduler_without_workers
    done, elapsed = sweep("--param", "epsilon=0.5", *SMALL, "--t-end", "10", "--fmu", fmu_file(3),
                          "--out", str(tmp_path / "r"), "--scheduler", f"127.0.0.1:{port}",
                          "--connect-timeout", "2", timeout=60)
    assert_one_line_error(done, f"the Dask scheduler at tcp://127.0.0.1:{port} has no workers",
                          f"dask worker tcp://127.0.0.1:{port}")
    assert elapsed < 60  # a hang guard; a 40-line traceback before


@pytest.mark.parametrize("args, words", [
    (["--param", "n_segments=100.5"], ["n_segments = 100.5 is not a whole number"]),
    (["--param", "epsilon=1.5"], ["epsilon = 1.5", "0.001 <= epsilon <= 1"]),
    (["--param", "mu=-1"], ["mu = -1", "0 <= mu <= 100"]),
    (["--param", "epsilon=abc"], ["--param epsilon=abc", "expected a:b:n"]),
    (["--param", "roundness=0.5"], ["not parameters of the FMU: roundness"]),
    (["--param", "epsilon=0.5", "--t-end", "0"], ["the horizon t_end must be a positive number, got 0"]),
    (["--param", "epsilon=0.5", "--t-end", "-5"], ["the horizon t_end must be a positive number, got -5"]),
    (["--param", "epsilon=0.5", "--t-end", "nan"], ["the horizon t_end must be a positive number"]),
    (["--param", "epsilon=0.5", "--t-end", "10.5"], ["not a whole number of record intervals"]),
    (["--param", "epsilon=0.5", "--t-end", "abc"], ["--t-end", "invalid float value"]),
    (["--param", "epsilon=0.5", "--scheduler", "localhost:port"], ["port must be a number"]),
    (["--param", "epsilon=0.5", "--connect-timeout", "0"], ["--connect-timeout", "must be a positive number"]),
    (["--t-end", "10"], ["--param"]),
    (["--param", "beta=0.5"], ["beta: the package takes this parameter as beta_deg"]),
    (["--param", "beta_deg=90"], ["beta_deg = 90 is invalid: the valid range is 0 <= beta_deg < 90"]),
    (["--param", "epsilon=-0.30"], ["epsilon = -0.3 is invalid"]),
    # the count was written out in 309 digits
    (["--param", "epsilon=0.5", "--t-end", "1e308"], ["1e+308 points to record"]),
    # the plate's vibration in the model's units: 2 pi f at most 1, A (2 pi f)^2 at most 10
    (["--param", "epsilon=0.5", "--vibration", "0.01,0.5"],
     ["--vibration 0.01,0.5", "vib_omega = 3.14159", "vib_omega <= 1"]),
    (["--param", "epsilon=0.5", "--vibration", "500,0.15"],
     ["--vibration 500,0.15", "vib_accel = ", "vib_accel <= 10"]),
    (["--param", "epsilon=0.5", "--vibration", "-1,0.1"],
     ["--vibration -1,0.1", "the amplitude -1", "0 or more"]),
    (["--param", "epsilon=0.5", "--vibration", "0.1,0"],
     ["--vibration 0.1,0", "the frequency 0", "above 0"]),
    (["--param", "epsilon=0.5", "--vibration", "0.1,0.1,120"],
     ["--vibration 0.1,0.1,120", "vib_angle_deg = 120", "90"]),
    (["--param", "epsilon=0.5", "--vibration", "0.1"],
     ["--vibration", "'0.1': expected AMPLITUDE,FREQUENCY[,ANGLE_DEG]"]),
    (["--param", "vib_omega=0.5", "--vibration", "0.1,0.1"],
     ["vib_omega is given twice: swept (--param) and by --vibration"]),
], ids=["integer", "range", "negative", "text", "unknown", "t_end 0", "t_end -5", "t_end nan",
        "t_end interval", "t_end text", "address", "timeout", "no param", "radians", "degrees",
        "as typed", "t_end huge", "vibration frequency", "vibration acceleration",
        "vibration amplitude", "vibration no frequency", "vibration angle", "vibration count",
        "vibration twice"])
def test_bad_values_are_one_line_before_anything_starts(fmu_file, tmp_path, args, words):
    done, elapsed = sweep(*args, "--fmu", fmu_file(3), "--out", str(tmp_path / "r"))
    assert_one_line_error(done, *words)
    assert not (tmp_path / "r" / "results.csv").exists()


def test_a_sweep_with_vibration_is_the_sweep_with_its_parameters_to_the_bit(fmu_file, tmp_path):
    """--vibration A,F,ANGLE (the model's units) is --param vib_accel=A(2 pi F)^2 --param
    vib_omega=2 pi F --param vib_angle_deg=ANGLE: the same keys, rows and numbers."""
    a, f, angle = 0.02, 0.005, 30.0
    omega = 2.0 * math.pi * f
    common = ["--param", "mu=0.1,0.5", *SMALL, "--t-end", "40", "--fmu", fmu_file(3),
              "--serial", "--no-plot"]
    given, _ = sweep(*common, "--vibration", f"{a},{f},{angle}", "--out", str(tmp_path / "v"))
    assert given.returncode == 0, given.stderr
    as_params = ["--param", f"vib_accel={a * omega * omega!r}", "--param", f"vib_omega={omega!r}",
                 "--param", f"vib_angle_deg={angle!r}"]
    spelled, _ = sweep(*common, *as_params, "--out", str(tmp_path / "p"))
    assert spelled.returncode == 0, spelled.stderr
    # the same set-up: in the first one's folder, they are its runs, none to run again
    again, _ = sweep(*common, *as_params, "--out", str(tmp_path / "v"))
    assert again.returncode == 0, again.stderr
    assert "0 executed, 2 already in the file" in again.stdout
    rows = [pd.read_csv(tmp_path / d / "results.csv", dtype=str).drop(columns=["cpu_s", "wall_s"])
            for d in ("v", "p")]
    pd.testing.assert_frame_equal(*rows)  # the text of every number: to the bit
    # rounded as every swept value is (batch/specs.py)
    assert float(rows[0]["vib_omega"][0]) == round(omega, DECIMALS)
    assert float(rows[0]["vib_accel"][0]) == round(a * omega * omega, DECIMALS) > 0
    # the plate vibrated: its work on the grain is in the rows of neither a still plate's
    still, _ = sweep(*common, "--out", str(tmp_path / "s"))
    assert still.returncode == 0, still.stderr
    assert not pd.read_csv(tmp_path / "s" / "results.csv")["Q_static_end"].equals(
        pd.read_csv(tmp_path / "v" / "results.csv")["Q_static_end"])


def test_unwritable_outputs_are_one_line_before_any_run(fmu_file, tmp_path):
    a_file = tmp_path / "a_file"
    a_file.write_text("")
    for out, says in ((a_file / "sweep", "cannot write"), ("/proc/tribo/sweep", "cannot write"),
                      (a_file, "cannot write"),
                      # --out is a folder, for every command: a file's name is refused, not
                      # made into a folder (or a file named like the folder)
                      (tmp_path / "new" / "results.csv", "--out names the output folder, not a file")):
        done, _ = sweep("--param", "epsilon=0.5", *SMALL, "--t-end", "10", "--fmu", fmu_file(3),
                        "--serial", "--out", str(out))
        assert_one_line_error(done, says)
    assert not (tmp_path / "new").exists()


def test_the_out_folder_is_made_with_its_parents(fmu_file, tmp_path):
    out = tmp_path / "new" / "dir" / "bad"
    done, _ = sweep("--param", "epsilon=0.5", *SMALL, "--t-end", "10", "--fmu", fmu_file(3),
                    "--serial", "--out", str(out), "--no-plot", "--series")
    assert done.returncode == 0, done.stderr
    assert out.is_dir() and (out / "results.csv").is_file() and (out / "series").is_dir()


def test_a_longer_horizon_goes_into_the_same_folder_and_fresh_keeps_a_backup(fmu_file, tmp_path):
    out = tmp_path / "sweep"
    base = ["--param", "epsilon=0.4,1.0", *SMALL, "--fmu", fmu_file(3), "--serial", "--out", str(out),
            "--no-plot"]
    first, _ = sweep(*base, "--t-end", "20")
    assert first.returncode == 0, first.stderr
    longer, _ = sweep(*base, "--t-end", "40")
    assert longer.returncode == 0, longer.stderr
    assert "2 executed, 0 already in the file" in longer.stdout
    df = pd.read_csv(out / "results.csv")
    assert sorted(df["t_end"]) == [20.0, 20.0, 40.0, 40.0]
    fresh, _ = sweep(*base, "--t-end", "20", "--fresh")
    assert fresh.returncode == 0, fresh.stderr
    backup = out / "backup-1"
    assert f"the earlier results are kept in {backup}" in fresh.stdout
    assert pd.read_csv(backup / "results.csv").equals(df) and len(pd.read_csv(out / "results.csv")) == 2


@pytest.mark.parametrize("where", [["--serial"], ["--workers", "2"], ["--processes", "--workers", "2"]],
                         ids=["serial", "dask threads", "dask processes"])
def test_ctrl_c_keeps_the_finished_runs_and_says_how_to_resume(fmu_file, tmp_path, where):
    """SIGINT to the whole process group, as Ctrl-C in a terminal sends it: one message, no
    traceback, no process left behind; the same command then runs only the rest."""
    out = tmp_path / "sweep" / "results.csv"
    cmd = [*subcommand("sweep"), "--param", "epsilon=0.2:1.0:6", "--param", "mu=1.0", *SMALL,
           "--t-end", "600", "--fmu", fmu_file(3), "--out", str(out.parent), "--no-plot", *where]
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and p.poll() is None:
        if out.exists() and len(out.read_text().splitlines()) >= 2:  # a run is kept
            break
        time.sleep(0.05)
    assert p.poll() is None, p.communicate()
    os.killpg(p.pid, signal.SIGINT)
    stdout, stderr = p.communicate(timeout=60)
    kept = len(pd.read_csv(out))
    assert p.returncode == 130, stderr
    assert "Traceback" not in stdout + stderr and "KeyboardInterrupt" not in stdout + stderr, stderr
    assert f"{kept} of 6 runs kept in {out}; run the same command to resume" in stderr
    assert 1 <= kept < 6
    deadline = time.monotonic() + 15
    while time.monotonic() < deadline and _session_alive(p.pid):
        time.sleep(0.1)
    assert not _session_alive(p.pid)  # the embedded cluster's workers are gone too
    again = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr
    assert f"{6 - kept} executed, {kept} already in the file, 0 failed; 6 of 6 runs done" in again.stdout


def test_ctrl_c_before_a_dask_call_starts_logs_no_traceback():
    """Ctrl-C while distributed's sync() waits for a coroutine that has not started yet: its
    cancel callback raises NameError on the event loop's thread (distributed 2026.8.0),
    which tornado would log with a traceback under a sweep's closing line. An executor
    puts a filter on tornado's logger that drops that record and keeps every other."""
    import inspect
    import logging

    import distributed.utils

    from tribo.batch.executors import INTERRUPTED_SYNC_FILTER

    # the callback as distributed has it, so that the filter matches the code it is for
    assert "def cancel() -> None:\n        if future is not None:" in inspect.getsource(
        distributed.utils.sync)

    def record_of(source, filename):
        scope = {}
        exec(compile(source, filename, "exec"), scope)
        try:
            scope["cancel"]()
        except Exception:
            return logging.LogRecord("tornado.application", logging.ERROR, __file__, 1,
                                     "Exception in callback %r", ("cancel",), sys.exc_info())
        raise AssertionError("the callback raised nothing")

    unset = "def cancel():\n    if future is not None:\n        pass\n"
    assert not INTERRUPTED_SYNC_FILTER.filter(record_of(unset, distributed.utils.__file__))
    # a NameError elsewhere, another error there, a record without an exception: logged
    assert INTERRUPTED_SYNC_FILTER.filter(record_of(unset, __file__))
    assert INTERRUPTED_SYNC_FILTER.filter(record_of("def cancel():\n    1 / 0\n",
                                                    distributed.utils.__file__))
    assert INTERRUPTED_SYNC_FILTER.filter(logging.LogRecord(
        "tornado.application", logging.ERROR, __file__, 1, "message", (), None))
    with DaskExecutor(workers=1):
        assert INTERRUPTED_SYNC_FILTER in logging.getLogger("tornado.application").filters


def test_what_dask_logs_while_closing_after_ctrl_c_is_not_shown():
    """After Ctrl-C the executor closes its cluster without showing what Dask and tornado
    log of the runs it stops (a worker's heartbeat to a scheduler that is closing, with
    its traceback, seen under load); without an interrupt, and once it is closed, their
    errors are logged as before."""
    import logging

    class Kept(logging.Handler):
        def __init__(self):
            super().__init__(logging.DEBUG)
            self.records = []

        def emit(self, record):
            self.records.append(record.getMessage())

    kept = Kept()
    logging.getLogger().addHandler(kept)
    try:
        for exc_type in (KeyboardInterrupt, None):
            executor = DaskExecutor(workers=1).__enter__()
            cluster_close = executor._cluster.close

            def close_logging(*args, **kwargs):
                logging.getLogger("distributed.worker").error("heartbeat failed")
                logging.getLogger("tornado.application").error("exception in callback")
                return cluster_close(*args, **kwargs)

            executor._cluster.close = close_logging
            executor.__exit__(exc_type, exc_type and exc_type(), None)
            shown = [m for m in kept.records if m in ("heartbeat failed", "exception in callback")]
            assert shown == ([] if exc_type else ["heartbeat failed", "exception in callback"])
            kept.records.clear()
        logging.getLogger("distributed.worker").error("after closing")
        assert "after closing" in kept.records
    finally:
        logging.getLogger().removeHandler(kept)


def _session_alive(sid):
    for q in psutil.process_iter(["pid"]):
        try:
            if os.getsid(q.pid) == sid:
                return True
        except (ProcessLookupError, PermissionError):
            pass
    return False


@pytest.mark.parametrize("processes", [False, True], ids=["threads", "processes"])
def test_the_embedded_cluster_listens_on_loopback_only_and_has_no_dashboard(processes):
    with DaskExecutor(workers=1, processes=processes) as executor:
        me = psutil.Process()
        listening = [c.laddr for q in [me] + me.children(recursive=True)
                     for c in q.net_connections(kind="inet") if c.status == psutil.CONN_LISTEN]
        assert listening and all(a.ip == "127.0.0.1" for a in listening), listening
        http = executor._cluster.scheduler.http_server.port
        assert http != 8787  # a free port, not Dask's default that other clusters take
        with pytest.raises(urllib.error.HTTPError) as e:
            urllib.request.urlopen(f"http://127.0.0.1:{http}/status", timeout=5)
        assert e.value.code == 404  # no dashboard pages


def test_the_sweep_plots_its_results(fmu_file, tmp_path):
    out = tmp_path / "results.csv"
    done, _ = sweep("--param", "epsilon=0.3,0.6,1.0", "--param", "mu=0.1,1.0", *SMALL, "--t-end", "30",
                    "--fmu", fmu_file(3), "--serial", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    png = tmp_path / "results.png"
    assert f"figure {png}" in done.stdout
    from matplotlib.image import imread
    assert imread(png).shape[0] >= 700

    from tribo.batch.plot import write_sweep_figure
    from tribo import plotting
    seen = {}
    original = plotting.save
    try:
        import tribo.batch.plot as sp
        sp.save = lambda fig, path: seen.setdefault("fig", fig)
        write_sweep_figure(pd.read_csv(out), ["epsilon", "mu"], str(tmp_path / "again.png"))
    finally:
        sp.save = original
    fig = seen["fig"]
    assert_legends_cover_no_data(fig)
    for ax in fig.axes:
        assert [t.get_text() for t in ax.get_legend().get_texts()] == ["mu = 0.1", "mu = 1"]
        assert ax.get_xlabel() == "epsilon"
        assert all(len(line.get_xdata()) == 3 for line in ax.get_lines())


def test_a_run_that_comes_to_rest_is_said_apart_in_the_rows_the_closing_line_and_the_figure(
        fmu_file, tmp_path):
    """With rolling resistance and the rigid stick a grain on a plate tilted 2 degrees settles
    and its run ends at rest before the horizon (seen: at tau ~ 448); at 45 degrees it runs
    to the horizon. The rows, the closing line and the figure say which."""
    done, _ = sweep("--param", "beta_deg=2,45", "--param", "mu_roll=0.05", "--param",
                    "stick_model=1", "--t-end", "500", "--no-progress", "--fmu", fmu_file(3),
                    "--serial", "--out", str(tmp_path))
    assert done.returncode == 0, done.stderr
    assert ("sweep: of the runs, 1 ran to the horizon, 1 came to rest on the chute, 0 left the "
            "chute") in done.stdout
    rows = pd.read_csv(tmp_path / "results.csv").set_index("beta_deg")
    assert (rows.loc[2.0, "end_reason"], rows.loc[2.0, "at_rest"], rows.loc[2.0, "exited"]) == (3, 1, 0)
    assert 0 < rows.loc[2.0, "rest_time"] < 500
    assert (rows.loc[45.0, "end_reason"], rows.loc[45.0, "rest_time"]) == (0, 0.0)

    from tribo.batch import plot as sp
    seen = {}
    original = sp.save
    try:
        sp.save = lambda fig, path: seen.setdefault("fig", fig)
        sp.write_sweep_figure(pd.read_csv(tmp_path / "results.csv"), ["beta_deg", "mu_roll",
                                                                     "stick_model"], "unused.png")
    finally:
        sp.save = original
    fig = seen["fig"]
    assert "1 came to rest on the chute" in fig._suptitle.get_text()
    for ax in fig.axes:
        rings = [line for line in ax.get_lines() if line.get_label() == sp.ENDED]
        assert len(rings) == 1 and list(rings[0].get_xdata()) == [2.0]
        assert [t.get_text() for t in ax.get_legend().get_texts()][-1] == sp.ENDED
    assert_legends_cover_no_data(fig)
