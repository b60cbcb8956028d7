"""tribo-sweep as a new user tries it: a scheduler that does not answer, or an address
without a scheme or port; bad values and horizons; unwritable outputs; Ctrl-C; a longer
horizon into the same file; --fresh; the embedded cluster's network exposure; the figure.
Each mistake is one line on stderr, before any cluster starts or any run is made."""

import os
import signal
import socket
import subprocess
import time
import urllib.error
import urllib.request

import pandas as pd
import psutil
import pytest

from study_support import command
from tribo.batch.executors import DaskExecutor, scheduler_address

SMALL = ["--param", "n_segments=64", "--no-progress"]


def sweep(*args, timeout=120):
    started = time.perf_counter()
    done = subprocess.run([command("tribo-sweep"), *args], capture_output=True, text=True,
                          timeout=timeout)
    return done, time.perf_counter() - started


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def assert_one_line_error(done, *words):
    assert done.returncode == 2, done
    lines = done.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("tribo-sweep: error: "), done.stderr
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
                          "--out", str(tmp_path / "r.csv"), "--scheduler", f"localhost:{port}",
                          "--connect-timeout", "2")
    assert_one_line_error(done, f"no Dask scheduler answered at tcp://localhost:{port} within 2 s")
    assert elapsed < 15  # was 31 s with Dask's default timeout; here the timeout and the start-up
    assert not (tmp_path / "r.csv").exists()


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
    (["--t-end", "10"], ["--param"]),
], ids=["integer", "range", "negative", "text", "unknown", "t_end 0", "t_end -5", "t_end nan",
        "t_end interval", "t_end text", "address", "no param"])
def test_bad_values_are_one_line_before_anything_starts(fmu_file, tmp_path, args, words):
    done, elapsed = sweep(*args, "--fmu", fmu_file(3), "--out", str(tmp_path / "r.csv"))
    assert_one_line_error(done, *words)
    assert not (tmp_path / "r.csv").exists()


def test_unwritable_outputs_are_one_line_before_any_run(fmu_file, tmp_path):
    a_file = tmp_path / "a_file"
    a_file.write_text("")
    for out in (a_file / "results.csv", "/proc/tribo/results.csv", tmp_path):
        done, _ = sweep("--param", "epsilon=0.5", *SMALL, "--t-end", "10", "--fmu", fmu_file(3),
                        "--serial", "--out", str(out))
        assert_one_line_error(done, "cannot write")
    done, _ = sweep("--param", "epsilon=0.5", *SMALL, "--t-end", "10", "--fmu", fmu_file(3), "--serial",
                    "--out", str(tmp_path / "r.csv"), "--series-dir", str(a_file / "series"))
    assert_one_line_error(done, "cannot write into", "a_file")
    assert not (tmp_path / "r.csv").exists()


def test_a_longer_horizon_goes_into_the_same_file_and_fresh_keeps_a_backup(fmu_file, tmp_path):
    out = tmp_path / "results.csv"
    base = ["--param", "epsilon=0.4,1.0", *SMALL, "--fmu", fmu_file(3), "--serial", "--out", str(out),
            "--no-plot"]
    first, _ = sweep(*base, "--t-end", "20")
    assert first.returncode == 0, first.stderr
    longer, _ = sweep(*base, "--t-end", "40")
    assert longer.returncode == 0, longer.stderr
    assert "2 executed, 0 already in the file" in longer.stdout
    df = pd.read_csv(out)
    assert sorted(df["t_end"]) == [20.0, 20.0, 40.0, 40.0]
    fresh, _ = sweep(*base, "--t-end", "20", "--fresh")
    assert fresh.returncode == 0, fresh.stderr
    backup = tmp_path / "results.backup-1.csv"
    assert f"the earlier results are kept in {backup}" in fresh.stdout
    assert pd.read_csv(backup).equals(df) and len(pd.read_csv(out)) == 2


@pytest.mark.parametrize("where", [["--serial"], ["--workers", "2"]], ids=["serial", "dask"])
def test_ctrl_c_keeps_the_finished_runs_and_says_how_to_resume(fmu_file, tmp_path, where):
    """SIGINT to the whole process group, as Ctrl-C in a terminal sends it: one message, no
    traceback, no process left behind; the same command then runs only the rest."""
    out = tmp_path / "results.csv"
    cmd = [command("tribo-sweep"), "--param", "epsilon=0.2:1.0:6", "--param", "mu=1.0", *SMALL,
           "--t-end", "600", "--fmu", fmu_file(3), "--out", str(out), "--no-plot", *where]
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


def _session_alive(sid):
    for q in psutil.process_iter(["pid"]):
        try:
            if os.getsid(q.pid) == sid:
                return True
        except (ProcessLookupError, PermissionError):
            pass
    return False


def test_the_embedded_cluster_listens_on_loopback_only_and_has_no_dashboard():
    with DaskExecutor(workers=1) as executor:
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
                    "--fmu", fmu_file(3), "--serial", "--out", str(out))
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
    for ax in fig.axes:
        assert [t.get_text() for t in ax.get_legend().get_texts()] == ["mu = 0.1", "mu = 1"]
        assert ax.get_xlabel() == "epsilon"
        assert all(len(line.get_xdata()) == 3 for line in ax.get_lines())
