"""The one flow every job into an output folder takes, from the API (tribo.sweep,
tribo.population, tribo.impact_map, tribo.line_*) and from the `tribo` command alike:

    report = execute(job, out, executor, fresh=False, progress=False, say=print)

1. `job.prepare()`: load the FMU image(s), make every run and check every value by the FMU
   (a mistake is one line: a ValueError of its concern); nothing runs, no cluster starts.
2. The output folder is checked writable and claimed (batch.folder.claim: its record of
   the set-up, its lock).
3. Inside the executor (a local cluster starts here), `job.run(...)`: the runs, recorded
   as they finish (batch.sweep.run_sweep), then the job's tables and figure.
4. The report (`Report`, or the job's subclass of it) with the folder's backup; the API
   raises on failed runs (`raise_on_failure`), a command prints them and exits 1.

A job is a concern's class with `kind` (its folder's kind, batch/folder.py), `noun` (what one
of its runs is), `results_file`, and `prepare`, `setup`, `describe`, `run` (see `Job`).
"""

import os
import tempfile
from dataclasses import dataclass, field

import pandas as pd

from .folder import claim
from .results import count_rows


@dataclass(kw_only=True)
class Report:
    """What a job did: the runs it is made of (their keys), how many this call executed,
    found finished (skipped) or failed, the finished runs' rows, the files written and
    where a fresh start moved the folder's earlier contents."""

    keys: list = field(default_factory=list)  # of every run of the job, in its order
    results: pd.DataFrame | None = None  # the rows of its finished runs, in its order
    executed: int = 0
    skipped: int = 0
    failed: list = field(default_factory=list)  # (spec, exception) of the runs that raised
    files: list = field(default_factory=list)
    backup: str | None = None
    notes: list = field(default_factory=list)  # lines to tell the user (rows dropped, ...)

    @property
    def total(self) -> int:
        return len(self.keys)

    @property
    def complete(self) -> bool:
        return self.results is not None and len(self.results) == len(self.keys)


class Job:
    """What a concern defines to run through `execute` (its attributes and methods)."""

    kind: str  # the output folder's kind (batch/folder.py's OWN_FILES)
    noun: str  # what one run is, for messages: "run", "particle", "episode", "grain"
    results_file: str  # the results file in the folder, its runs appended as they finish
    sha256: str  # of the FMU image(s) the runs use, once prepared
    keys: list  # of the runs, once prepared (empty where they are not known beforehand)

    def prepare(self) -> None:
        """Load the FMU(s), make the runs, check every value; nothing runs."""
        raise NotImplementedError

    def setup(self) -> dict:
        """What makes the folder's results this job's (plain JSON values)."""
        raise NotImplementedError

    def describe(self, out: str, executor) -> str:
        """The line said when the runs start."""
        raise NotImplementedError

    def run(self, out: str, executor, *, progress: bool, max_runs: int | None) -> Report:
        raise NotImplementedError

    def results_path(self, out: str) -> str:
        """The results file the runs are appended to (what an interrupted job keeps)."""
        return os.path.join(out, self.results_file)


def execute(job: Job, out: str, executor, *, fresh: bool = False, progress: bool = False,
            max_runs: int | None = None, say=None) -> Report:
    """Run `job` into the folder `out` (see the module's text). `say(line)` is told what
    happens to the folder and when the runs start (default: nothing)."""
    say = say or (lambda line: None)
    job.prepare()
    if max_runs is not None and (isinstance(max_runs, bool) or not isinstance(max_runs, int)
                                 or max_runs < 0):
        raise ValueError(f"max_runs = {max_runs!r}: a whole number, at least 0")
    check_out_folder(out)
    check_writable_dir(out)
    with claim(out, job.kind, job.setup(), job.sha256, fresh) as folder:
        if folder.note:
            say(f"{job.kind}: {folder.note}")
        with executor:
            say(job.describe(out, executor))
            report = job.run(out, executor, progress=progress, max_runs=max_runs)
    report.backup = folder.backup or report.backup
    return report


def raise_on_failure(report: Report, noun: str) -> Report:
    """The report, or RuntimeError naming the first failed run's error."""
    if report.failed:
        _, error = report.failed[0]
        raise RuntimeError(f"{len(report.failed)} {noun}(s) failed, e.g.: {error}")
    return report


def kept(job: Job, out: str) -> str:
    """What an interrupted job keeps, in words: "3 of 6 particles kept in <file>"."""
    path = job.results_path(out)
    n = count_rows(path, job.keys or None)
    of = f" of {len(job.keys)}" if job.keys else ""
    return f"{n}{of} {job.noun}s kept in {path}"


def check_out_folder(out: str) -> None:
    """ValueError, one line, for an `out` that names a file (a table, a figure) rather
    than the folder the files go into."""
    if str(out).lower().endswith((".csv", ".png", ".json")):
        parent = os.path.dirname(out) or "."
        raise ValueError(f"{out}: --out names the output folder, not a file (the results go "
                         f"into it): e.g. {parent}")


def check_writable_dir(path: str) -> None:
    """OSError, naming the path, unless files can be made in the folder (made if missing)."""
    if os.path.exists(path) and not os.path.isdir(path):
        raise OSError(f"cannot write into {path}: a file, not a folder")
    try:
        os.makedirs(path, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path, prefix=".tribo_write_check_"):
            pass
    except OSError as e:
        raise OSError(f"cannot write into {path}: {e.strerror or e}") from None

