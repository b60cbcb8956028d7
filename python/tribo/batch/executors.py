"""Where runs execute: in this process, one after the other (`SerialExecutor`), or as
Dask tasks (`DaskExecutor`): by default on a local cluster embedded in this process
(one worker process per core, one thread each: a run is single-threaded C), or on an
existing cluster when given its scheduler address.

The embedded cluster listens on 127.0.0.1 only and opens no dashboard (its scheduler's
HTTP server, which Dask always starts, takes a free port on 127.0.0.1 and serves no
dashboard pages). Its worker processes ignore SIGINT: Ctrl-C in a terminal reaches the
whole process group, and it is this process that stops the sweep and closes the cluster.

Both have the same interface: a context manager whose `run(function, image, specs)`
yields (index into specs, RunResult or the exception the run raised) as runs finish.
A run's numbers do not depend on where it ran: every task loads the FMU from the bytes
it is given and runs it from its initial state.
"""

import contextlib
import logging
import os
import signal
import tempfile
import threading
import zipfile
from typing import Callable, Iterator

# the whole package (tribo/, above batch/) goes to the workers of an existing cluster
PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_SCHEDULER_PORT = 8786  # Dask's
CONNECT_TIMEOUT_S = 5.0


class ClusterUnreachable(ConnectionError):
    """The scheduler at the address given did not answer (the message says where and how
    long it was tried)."""


def scheduler_address(text: str) -> str:
    """A Dask scheduler address as Dask takes it: "host", "host:port" and
    "tcp://host[:port]" become "tcp://host:port" (port 8786, Dask's default, when none is
    given). ValueError, saying why, for anything else."""
    text = text.strip()
    scheme, sep, rest = text.partition("://")
    if not sep:
        scheme, rest = "tcp", text
    if scheme not in ("tcp", "tls", "ws", "wss"):
        raise ValueError(f"--scheduler {text}: unknown protocol {scheme!r} (tcp, tls, ws or wss)")
    if rest.startswith("["):  # [IPv6]:port
        host, _, port = rest[1:].partition("]")
        port = port[1:] if port.startswith(":") else ""
        host = f"[{host}]"
    else:
        host, _, port = rest.partition(":")
    if not host.strip("[]") or "/" in host or ":" in port:
        raise ValueError(f"--scheduler {text}: expected [tcp://]host[:port]")
    if port and not (port.isdigit() and 0 < int(port) < 65536):
        raise ValueError(f"--scheduler {text}: the port must be a number from 1 to 65535")
    return f"{scheme}://{host}:{port or DEFAULT_SCHEDULER_PORT}"


def available_cores() -> int:
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


class SerialExecutor:
    """Runs in this process, in order."""

    workers = 1

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def describe(self) -> str:
        return "serial, in this process"

    def run(self, function: Callable, image, specs) -> Iterator:
        for i, spec in enumerate(specs):
            with _sigint_held() as interrupted:
                try:
                    result = function(image, spec)
                except Exception as e:  # one failed run does not stop the sweep
                    result = e
            yield i, result
            if interrupted:  # after the run is handed over, so that it is kept
                raise KeyboardInterrupt


class DaskExecutor:
    """Runs as Dask tasks: a local cluster of `workers` processes (default: one per
    core), or the existing cluster at `address` (e.g. "tcp://10.0.0.5:8786", see
    `scheduler_address`), whose workers receive this package on connection (they need
    fmpy, numpy and pandas). An address that does not answer within `connect_timeout`
    seconds raises ClusterUnreachable."""

    def __init__(self, address: str | None = None, workers: int | None = None,
                 connect_timeout: float = CONNECT_TIMEOUT_S):
        self.address = scheduler_address(address) if address else None
        self.n_workers = workers or available_cores()
        self.connect_timeout = connect_timeout
        self._cluster = None
        self._client = None
        self._scattered = {}  # FMU sha256 -> future of its image on the workers

    def __enter__(self):
        # distributed only when a Dask run starts: `import tribo` and serial runs stay without it
        from distributed import Client, LocalCluster

        if self.address:
            try:
                self._client = Client(self.address, timeout=self.connect_timeout)
            except OSError as e:
                raise ClusterUnreachable(
                    f"no Dask scheduler answered at {self.address} within "
                    f"{self.connect_timeout:g} s ({_first_line(e)})") from None
            _ship_package(self._client)
        else:
            with _sigint_ignored():  # inherited by the worker processes
                self._cluster = LocalCluster(
                    n_workers=self.n_workers, threads_per_worker=1, processes=True,
                    host="127.0.0.1", dashboard_address=None,
                    scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"},
                    silence_logs=logging.ERROR)
            self._client = Client(self._cluster)
        return self

    def __exit__(self, exc_type, *exc):
        self._scattered.clear()
        # after Ctrl-C, a second one does not cut the closing short
        quiet = _sigint_ignored() if exc_type is not None and issubclass(exc_type, KeyboardInterrupt) \
            else contextlib.nullcontext()
        with quiet:
            if self._client is not None:
                self._client.close()
            if self._cluster is not None:
                self._cluster.close()
        self._client = self._cluster = None
        return False

    @property
    def client(self):
        return self._client

    @property
    def workers(self) -> int:
        """Runs that execute at once: the cluster's worker threads."""
        info = self._client.scheduler_info(n_workers=-1)["workers"]
        return max(1, sum(w.get("nthreads", 1) for w in info.values()))

    def describe(self) -> str:
        where = self.address or f"local cluster ({self.n_workers} worker processes)"
        return f"Dask, {where}"

    def run(self, function: Callable, image, specs) -> Iterator:
        from distributed import as_completed  # lazily, as in __enter__

        if image.sha256 not in self._scattered:
            self._scattered[image.sha256] = self._client.scatter(image, broadcast=True)
        image_future = self._scattered[image.sha256]
        futures = [self._client.submit(function, image_future, spec, pure=False) for spec in specs]
        index = {f.key: i for i, f in enumerate(futures)}
        try:
            for future in as_completed(futures):
                i = index[future.key]
                try:
                    result = future.result()
                except Exception as e:
                    yield i, e
                else:
                    yield i, result
                future.release()
        finally:
            for f in futures:
                f.cancel()


def _ship_package(client) -> None:
    """Send this package to the cluster's workers (present and future) as a zip on
    their sys.path, so that the task functions unpickle there."""
    with tempfile.TemporaryDirectory(prefix="tribo_pkg_") as tmp:
        archive = os.path.join(tmp, "tribo.zip")
        name = os.path.basename(PACKAGE_DIR)
        with zipfile.ZipFile(archive, "w") as z:
            for folder, dirs, files in os.walk(PACKAGE_DIR):
                dirs[:] = sorted(d for d in dirs if d != "__pycache__")
                for f in sorted(files):
                    if not f.endswith((".pyc", ".pyo")):
                        path = os.path.join(folder, f)
                        z.write(path, os.path.join(name, os.path.relpath(path, PACKAGE_DIR)))
        client.upload_file(archive, load=True)


@contextlib.contextmanager
def _sigint_held():
    """Ctrl-C during a run is held until the run returns (the list it gives is then not
    empty): a KeyboardInterrupt raised while the FMU calls its logger, a ctypes callback,
    would be printed and dropped by ctypes, and the run would go on. A second Ctrl-C
    interrupts at once."""
    interrupted = []
    if threading.current_thread() is not threading.main_thread():  # only it has signals
        yield interrupted
        return

    def hold(signum, frame):
        interrupted.append(signum)
        signal.signal(signal.SIGINT, previous)

    previous = signal.signal(signal.SIGINT, hold)
    try:
        yield interrupted
    finally:
        signal.signal(signal.SIGINT, previous)


@contextlib.contextmanager
def _sigint_ignored():
    if threading.current_thread() is not threading.main_thread():  # only it has signals
        yield
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


def _first_line(e: BaseException) -> str:
    text = str(e).strip() or type(e).__name__
    return text.splitlines()[0]
