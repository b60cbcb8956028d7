"""Where runs execute: in this process, one after the other (`SerialExecutor`), or as
Dask tasks (`DaskExecutor`): by default on a local cluster embedded in this process, or
on an existing cluster when given its scheduler address.

The local cluster runs its tasks in threads of this process, one per core: the FMU's
calls release the GIL (ctypes), so runs proceed in parallel, and no process is spawned,
which would import the user's script again in each worker (a script without an
`if __name__ == "__main__":` guard would start clusters recursively where worker
processes are spawned, that is not on Linux: `worker_start_method`); docs/sweeps.md has
the measurement against worker processes, which `processes=True` still gives. The
cluster's scheduler and workers talk in-process (with processes: over 127.0.0.1), and it
opens no dashboard: the HTTP servers Dask always starts take free ports on 127.0.0.1 and
serve no dashboard pages. Worker processes ignore SIGINT: Ctrl-C in a
terminal reaches the whole process group, and it is this process that stops the sweep
and closes the cluster.

An existing cluster is checked before it is used, each mistake one line within the
connect timeout: nothing listening, something that is not a Dask scheduler (a Dask
scheduler speaks first on connection; an HTTP server, such as its dashboard, waits for a
request), a scheduler without workers.

Both have the same interface: a context manager whose `run(function, image, specs)`
yields (index into specs, RunResult or the exception the run raised) as runs finish.
A run's numbers do not depend on where it ran: every task loads the FMU from the bytes
it is given and runs it from its initial state.
"""

import contextlib
import logging
import os
import signal
import socket
import sys
import tempfile
import threading
import time
import zipfile
from typing import Callable, Iterator

from ..fmu.reuse import Instances, runs_share_instances

# the whole package (tribo/, above batch/) goes to the workers of an existing cluster
PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DEFAULT_SCHEDULER_PORT = 8786  # Dask's
CONNECT_TIMEOUT_S = 5.0
# what a Dask scheduler's first message (its handshake) holds, in msgpack
DASK_HANDSHAKE = b"compression"


class ClusterUnreachable(ConnectionError):
    """The scheduler at the address given did not answer, is not a Dask scheduler or has
    no workers (the message says which, where and how long it was tried)."""


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


class _InterruptedSyncFilter(logging.Filter):
    """Drops the one record Ctrl-C makes Dask's event loop log with a traceback: when the
    interrupt comes before the coroutine of distributed's `sync` has started, the
    callback that cancels it (`cancel` in distributed/utils.py) reads a variable not yet
    set and raises NameError (distributed 2026.8.0), which tornado logs on its loop
    thread. The sweep has stopped as asked by then; any other record passes."""

    def filter(self, record: logging.LogRecord) -> bool:
        exc = record.exc_info[1] if record.exc_info else None
        if not isinstance(exc, NameError) or exc.__traceback__ is None:
            return True
        tb = exc.__traceback__
        while tb.tb_next is not None:
            tb = tb.tb_next
        code = tb.tb_frame.f_code
        return not (code.co_name == "cancel"
                    and code.co_filename.replace(os.sep, "/").endswith("distributed/utils.py"))


INTERRUPTED_SYNC_FILTER = _InterruptedSyncFilter()


class SerialExecutor:
    """Runs in this process, in order."""

    workers = 1

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def describe(self) -> str:
        return "serial, in this process"

    def run(self, function: Callable, image, specs, task_runs: int | None = None) -> Iterator:
        # task_runs: DaskExecutor's; a serial run is one run at a time
        with _runs(function, image, specs) as runs:
            for i in range(len(specs)):
                with _sigint_held() as interrupted:
                    result = next(runs)
                yield i, result
                if interrupted:  # after the run is handed over, so that it is kept
                    raise KeyboardInterrupt


def executor_for(serial: bool = False, scheduler: str | None = None, workers: int | None = None,
                 processes: bool = False, connect_timeout: float = CONNECT_TIMEOUT_S):
    """The executor of the API's and the commands' options: SerialExecutor (serial), or a
    DaskExecutor (ValueError for an address Dask does not take). Nothing starts until it
    is entered."""
    if serial:
        return SerialExecutor()
    return DaskExecutor(scheduler, workers, connect_timeout=connect_timeout, processes=processes)


# What the local cluster's servers do besides the runs, made rarer or left out: each of them
# (the scheduler, each worker and its nanny, the client) wakes every 20 ms to see whether its
# event loop is blocked, 10 times a second to read its memory and twice to record the
# system's load for a dashboard, and each worker samples its threads' stacks every 10 ms
# for a profile no one reads (the cluster serves no dashboard). Together that was an eighth
# of the CPU of 400 grains of the reference feed on 2 workers, threads or processes
# (docs/populations.md, "Benchmark"). An existing cluster keeps its own settings.
LOCAL_CLUSTER_CONFIG = {
    "distributed.admin.tick.interval": "1s",
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.profile.enabled": False,
}


def worker_start_method() -> str:
    """How the local cluster starts its worker processes: forked from this process on Linux,
    where Dask spawns them by default. A spawned worker imports Dask, numpy and the task's
    modules before its first run (0.45 s of CPU each here, a tenth of the core's CPU for
    1000 grains of the reference feed: docs/populations.md, "Benchmark") and runs the
    user's script again (as __mp_main__); a forked one has them and does not. The fork is
    taken as the cluster starts, by Dask's nanny from a thread of its own: Python makes its
    import and logging locks anew in the child and multiprocessing its queues; the child
    keeps the FMU its parent loaded (fmu/library.py). A run's numbers do not depend on it:
    every task loads the FMU image it is given and runs from its initial state. Elsewhere
    spawned, as Dask does: macOS's system libraries are not safe in a forked child of a
    process with threads, and Windows has no fork."""
    return "fork" if sys.platform.startswith("linux") else "spawn"


# a task holds at most this many runs, and each worker gets at least TASKS_PER_WORKER tasks
# where there are runs enough: the slowest grain's task then ends about as the others do
RUNS_PER_TASK = 64
TASKS_PER_WORKER = 4


def runs_per_task(runs: int, workers: int, most: int = RUNS_PER_TASK) -> int:
    """How many runs one Dask task holds (at most `most`), for `runs` runs on `workers`
    worker threads."""
    return max(1, min(most, runs // (TASKS_PER_WORKER * max(1, workers))))


def run_each(function: Callable, image, specs) -> list:
    """A Dask task of several runs: each run's result, or the exception it raised, in the
    order of `specs` (one failed run does not stop the others)."""
    with _runs(function, image, specs) as runs:
        return list(runs)


@contextlib.contextmanager
def _runs(function: Callable, image, specs):
    """An iterator of each run's result, or the exception it raised, in the order of
    `specs`; the runs of a function that shares instances (fmu/reuse.py) share one task's
    `Instances`, freed when the block ends."""
    instances = Instances() if runs_share_instances(function) else None

    def each():
        for spec in specs:
            try:
                yield (function(image, spec) if instances is None
                       else function(image, spec, instances))
            except Exception as e:  # one failed run does not stop the others
                yield e

    try:
        yield each()
    finally:
        if instances is not None:
            instances.close()


class DaskExecutor:
    """Runs as Dask tasks: a local cluster of `workers` threads (default: one per core;
    processes=True: worker processes, one thread each), or the existing cluster at
    `address` (e.g. "tcp://10.0.0.5:8786", see `scheduler_address`), whose workers receive
    this package on connection (they need fmpy, numpy and pandas). An address where no
    Dask scheduler with workers answers within `connect_timeout` seconds raises
    ClusterUnreachable. `task_runs`: the most runs one task holds (runs_per_task)."""

    def __init__(self, address: str | None = None, workers: int | None = None,
                 connect_timeout: float = CONNECT_TIMEOUT_S, processes: bool = False,
                 task_runs: int | None = None):
        if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                    or workers < 1):
            raise ValueError(f"workers = {workers!r}: a whole number, at least 1")
        if task_runs is not None and (isinstance(task_runs, bool) or not isinstance(task_runs, int)
                                      or task_runs < 1):
            raise ValueError(f"task_runs = {task_runs!r}: a whole number, at least 1")
        if not (isinstance(connect_timeout, (int, float)) and connect_timeout > 0
                and connect_timeout < float("inf")):
            raise ValueError(f"connect timeout = {connect_timeout!r}: a positive number of seconds")
        self.address = scheduler_address(address) if address else None
        self.n_workers = workers or available_cores()
        self.connect_timeout = float(connect_timeout)
        self.processes = processes
        self.task_runs = task_runs or RUNS_PER_TASK  # the most runs a task holds (run)
        self._cluster = None
        self._client = None
        self._scattered = {}  # FMU sha256 -> future of its image on the workers

    def __enter__(self):
        # distributed only when a Dask run starts: `import tribo` and serial runs stay without it
        from distributed import Client, LocalCluster

        logging.getLogger("tornado.application").addFilter(INTERRUPTED_SYNC_FILTER)  # (added once)

        if self.address:
            self._client = _connect(self.address, self.connect_timeout)
            _ship_package(self._client)
            return self
        # dask only when a Dask run starts, as distributed above
        import dask

        # taken by each server, and by each nanny for its worker process, as it starts
        with dask.config.set({**LOCAL_CLUSTER_CONFIG,
                              "distributed.worker.multiprocessing-method": worker_start_method()}):
            self._start_local(Client, LocalCluster)
        return self

    def _start_local(self, Client, LocalCluster):
        """The local cluster (threads, or worker processes) and its client."""
        if self.processes:
            # the worker processes' own logs are not the command's: a run's failure comes
            # back with its result, and after Ctrl-C a worker's heartbeat to the scheduler
            # that is closing logs an error with a traceback
            with _sigint_ignored():  # inherited by the worker processes
                self._cluster = LocalCluster(
                    n_workers=self.n_workers, threads_per_worker=1, processes=True,
                    host="127.0.0.1", dashboard_address=None,
                    scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"},
                    silence_logs=logging.CRITICAL)
            self._client = Client(self._cluster)
        else:
            # in-process: the scheduler and the worker talk through memory; their HTTP
            # servers on 127.0.0.1 (Dask's default for the worker's is every interface)
            self._cluster = LocalCluster(
                n_workers=1, threads_per_worker=self.n_workers, processes=False,
                dashboard_address=None, worker_dashboard_address="127.0.0.1:0",
                scheduler_kwargs={"dashboard": False, "dashboard_address": "127.0.0.1:0"},
                silence_logs=logging.ERROR)
            self._client = Client(self._cluster)

    def __exit__(self, exc_type, *exc):
        self._scattered.clear()
        interrupted = exc_type is not None and issubclass(exc_type, KeyboardInterrupt)
        # after Ctrl-C, a second one does not cut the closing short, and what Dask logs of
        # the runs it is stopping is not an error to show
        with (_sigint_ignored() if interrupted else contextlib.nullcontext()), \
                (_logs_silenced() if interrupted else contextlib.nullcontext()):
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
        kind = "worker processes" if self.processes else "threads"
        where = self.address or f"local cluster ({self.n_workers} {kind})"
        return f"Dask, {where}"

    def run(self, function: Callable, image, specs, task_runs: int | None = None) -> Iterator:
        """The runs as tasks of `runs_per_task` runs each (at most `task_runs`, default the
        executor's: runs much shorter than a grain's, such as impact episodes, take more a
        task): a task costs the scheduler, the worker and this process some milliseconds of
        CPU, as much as a grain's run, so that a task per run would double a population's
        CPU (docs/populations.md, "Benchmark"). An interrupted sweep loses the runs of the
        tasks in flight."""
        from distributed import as_completed  # lazily, as in __enter__

        if image.sha256 not in self._scattered:
            self._scattered[image.sha256] = self._client.scatter(image, broadcast=True)
        image_future = self._scattered[image.sha256]
        size = runs_per_task(len(specs), self.n_workers if self.address is None else self.workers,
                             task_runs or self.task_runs)
        starts = range(0, len(specs), size)
        futures = [self._client.submit(run_each, function, image_future, specs[i:i + size],
                                       pure=False) for i in starts]
        first = {f.key: i for i, f in zip(starts, futures)}
        try:
            for future in as_completed(futures):
                i = first[future.key]
                try:
                    results = future.result()
                except Exception as e:  # the task itself failed (a worker lost): each run did
                    results = [e] * len(specs[i:i + size])
                for k, result in enumerate(results):
                    yield i + k, result
                future.release()
        finally:
            for f in futures:
                f.cancel()


def _connect(address: str, timeout: float):
    """A client of the Dask scheduler at `address` that has at least one worker, all
    within `timeout` seconds; ClusterUnreachable, in one line, otherwise."""
    from distributed import Client  # lazily, as in DaskExecutor.__enter__

    deadline = time.monotonic() + timeout
    _probe(address, timeout)
    try:
        client = Client(address, timeout=max(0.1, deadline - time.monotonic()))
    except (OSError, TimeoutError) as e:
        raise ClusterUnreachable(f"no Dask scheduler answered at {address} within {timeout:g} s "
                                 f"({_first_line(e)})") from None
    try:
        client.wait_for_workers(1, timeout=max(0.1, deadline - time.monotonic()))
    except (OSError, TimeoutError):
        client.close()
        raise ClusterUnreachable(f"the Dask scheduler at {address} has no workers (none joined "
                                 f"within {timeout:g} s): start one with `dask worker {address}`") from None
    return client


def _probe(address: str, timeout: float) -> None:
    """Connect to a tcp:// address and read what it says first: a Dask scheduler sends its
    handshake at once; anything else (an HTTP server waits for a request) would leave
    Dask's client waiting for ever. Other protocols (tls, ws) are left to Dask."""
    scheme, _, rest = address.partition("://")
    if scheme != "tcp":
        return
    host, _, port = rest.rpartition(":")
    deadline = time.monotonic() + timeout
    try:
        sock = socket.create_connection((host.strip("[]"), int(port)), timeout=timeout)
    except OSError as e:
        why = "no answer" if isinstance(e, socket.timeout) else (e.strerror or type(e).__name__).lower()
        raise ClusterUnreachable(f"no Dask scheduler answered at {address} within {timeout:g} s "
                                 f"({why})") from None
    said = b""
    with sock:
        try:
            while DASK_HANDSHAKE not in said and len(said) < 4096:
                sock.settimeout(max(0.01, deadline - time.monotonic()))
                chunk = sock.recv(4096)
                if not chunk:
                    break
                said += chunk
        except OSError:  # the time is up, or the peer hung up
            pass
    if DASK_HANDSHAKE not in said:
        what = "said nothing" if not said else "spoke another protocol"
        raise ClusterUnreachable(f"{address} is not a Dask scheduler: it took the connection but "
                                 f"{what} within {timeout:g} s (an HTTP server, such as a "
                                 f"dashboard? Dask schedulers listen on port {DEFAULT_SCHEDULER_PORT} "
                                 f"unless told otherwise)")


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


@contextlib.contextmanager
def _logs_silenced():
    """No record below critical is logged in this process until the block ends (Dask and
    tornado give some of their loggers levels of their own, so all of them)."""
    previous = logging.root.manager.disable
    logging.disable(logging.ERROR)
    try:
        yield
    finally:
        logging.disable(previous)


def _first_line(e: BaseException) -> str:
    text = str(e).strip() or type(e).__name__
    return text.splitlines()[0]
