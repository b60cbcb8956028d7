"""Where runs execute: in this process, one after the other (`SerialExecutor`), or as
Dask tasks (`DaskExecutor`): by default on a local cluster embedded in this process
(one worker process per core, one thread each: a run is single-threaded C), or on an
existing cluster when given its scheduler address.

Both have the same interface: a context manager whose `run(function, image, specs)`
yields (index into specs, RunResult or the exception the run raised) as runs finish.
A run's numbers do not depend on where it ran: every task loads the FMU from the bytes
it is given and runs it from its initial state.
"""

import logging
import os
import tempfile
import zipfile
from typing import Callable, Iterator

PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))


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
            try:
                result = function(image, spec)
            except Exception as e:  # one failed run does not stop the sweep
                yield i, e
            else:
                yield i, result


class DaskExecutor:
    """Runs as Dask tasks: a local cluster of `workers` processes (default: one per
    core), or the existing cluster at `address` (e.g. "tcp://10.0.0.5:8786"), whose
    workers receive this package on connection (they need fmpy, numpy and pandas)."""

    def __init__(self, address: str | None = None, workers: int | None = None):
        self.address = address
        self.n_workers = workers or available_cores()
        self._cluster = None
        self._client = None
        self._scattered = {}  # FMU sha256 -> future of its image on the workers

    def __enter__(self):
        from distributed import Client, LocalCluster

        if self.address:
            self._client = Client(self.address)
            _ship_package(self._client)
        else:
            self._cluster = LocalCluster(n_workers=self.n_workers, threads_per_worker=1,
                                         processes=True, dashboard_address=None,
                                         silence_logs=logging.ERROR)
            self._client = Client(self._cluster)
        return self

    def __exit__(self, *exc):
        self._scattered.clear()
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
        from distributed import as_completed

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
    with tempfile.TemporaryDirectory(prefix="tribo_study_pkg_") as tmp:
        archive = os.path.join(tmp, "tribo_study.zip")
        with zipfile.ZipFile(archive, "w") as z:
            for name in sorted(os.listdir(PACKAGE_DIR)):
                if name.endswith(".py"):
                    z.write(os.path.join(PACKAGE_DIR, name), f"tribo_study/{name}")
        client.upload_file(archive, load=True)
