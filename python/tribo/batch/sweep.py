"""A parameter sweep: many runs, each recorded as it finishes, resumable.

`run_sweep` keys every run (specs.run_key), skips the runs whose rows are already in the
results file (and whose time series are on disk, if series are kept), runs the rest on
the executor, and appends each finished run's row to the file at once. Interrupt it at
any point and call it again with the same runs: only the unfinished ones run. The file is
read once, when the sweep opens it (batch/results.py: a row that does not read back is
left out and its run runs again), and once at the end, for the report's rows (a file that
holds exactly the sweep's runs, all finished, is put in the sweep's order; a file shared by
several sweeps keeps the order its rows came in). Runs of different horizons share the
columns, so they can share a file.
"""

import io
import os

import pandas as pd
from tqdm.auto import tqdm

from ..fmu.charge_models import mean_charges
from .job import Report
from .particle import run_fmu
from .results import KEY, ResultsFile, table_csv
from .specs import RunSpec, run_key
from .summary import summary_columns

RUN_COLUMNS = ["t_end", "record_interval", "fmu_sha256"]
# what a sweep writes into its output folder (--out, out=)
RESULTS, FIGURE, SERIES = "results.csv", "results.png", "series"
TIMING_COLUMNS = ["cpu_s", "wall_s"]  # differ from one execution of a run to the next

PROGRESS_DELAY = 2.0  # s before a progress bar shows (tqdm's delay)


def sweep_columns(specs: list[RunSpec], results: list[str], constants: dict | None = None) -> list[str]:
    """The results file's header: the key, the constants (e.g. the materials), the
    parameters, the run's set-up, the result columns and the timings."""
    names = list(specs[0].params)
    if any(list(s.params) != names for s in specs):
        raise ValueError("the runs of one sweep must set the same parameters")
    return [KEY] + list(constants or {}) + names + RUN_COLUMNS + list(results) + TIMING_COLUMNS


def text_columns(specs: list[RunSpec], constants: dict) -> list[str]:
    """The columns that hold text (a material's name): every other one holds numbers."""
    return [name for name, value in {**constants, **specs[0].params}.items()
            if isinstance(value, str)]


def sweep_setup(swept: list[str], base: str, tie: bool) -> dict:
    """What gives a sweep's rows their meaning beyond their columns (an output folder's
    record, batch/folder.py): the parameters swept (the rows of other values or horizons
    of the same ones can share the folder), the base of the others, whether nu and tau_r
    follow mu and tau0."""
    return {"swept": list(swept), "base": base, "tie": bool(tie)}


def keys_of(specs: list[RunSpec], image) -> list[str]:
    """The sweep's run keys, each once, in the sweep's order."""
    return list(dict.fromkeys(run_key(s, image.sha256) for s in specs))


def run_sweep(specs: list[RunSpec], image, results_path: str, executor, *,
              resume: bool = True, series_dir: str | None = None, max_runs: int | None = None,
              progress: bool = True, desc: str = "runs", run=run_fmu,
              result_columns: list[str] | None = None, constants: dict | None = None,
              task_runs: int | None = None) -> Report:
    """Run `specs` (skipping finished ones if `resume`), appending a row per finished run
    to `results_path` and, if `series_dir` is given, writing each run's time series to
    <series_dir>/<key>.csv. `max_runs` caps the runs this call executes (the rest stay
    to be done). `run(image, spec)` -> RunResult is the function the executor runs;
    `result_columns` the names of its row (default: the study's summary of the FMU's
    charge models); `constants` columns with the same value on every row (what the runs
    share but do not pass to the FMU by name, e.g. the materials' names), after the key;
    `task_runs` the most runs a Dask task holds (the executor's default if None).
    The report's results are the finished runs' rows, in the sweep's order."""
    keys = [run_key(s, image.sha256) for s in specs]
    unique = list(dict.fromkeys(keys))
    spec_of = dict(zip(keys, specs))
    constants = dict(constants or {})
    if result_columns is None:
        result_columns = summary_columns(mean_charges(image.model_description()))
    results = ResultsFile(results_path, sweep_columns(specs, result_columns, constants),
                          fresh=not resume, text_columns=text_columns(specs, constants))
    if series_dir:
        series_dir = os.path.abspath(series_dir)  # as the results file's path (results.py)
        os.makedirs(series_dir, exist_ok=True)

    def finished(key):
        return series_dir is None or os.path.exists(series_path(series_dir, key))

    done = results.finished  # a set made once, not per key
    todo = [k for k in unique if not (k in done and finished(k))]
    report = Report(keys=unique, skipped=len(unique) - len(todo), backup=results.backup,
                    notes=[results.note] if results.note else [])
    if max_runs is not None:
        todo = todo[:max_runs]

    # a bar shows once the runs have taken PROGRESS_DELAY s: a study's short phases draw none
    with tqdm(total=len(todo), desc=desc, unit="run", disable=not progress or not todo,
              dynamic_ncols=True, delay=PROGRESS_DELAY) as bar:
        try:
            for i, outcome in executor.run(run, image, [spec_of[k] for k in todo],
                                           task_runs=task_runs):
                key, spec = todo[i], spec_of[todo[i]]
                bar.update()
                if isinstance(outcome, BaseException):
                    report.failed.append((spec, outcome))
                    bar.write(f"run {key} failed: {outcome}")
                    continue
                if series_dir:  # first the series, so that a row in the file implies its series
                    if outcome.segments is not None:
                        write_series(outcome.segments, segments_path(series_dir, key))
                    write_series(outcome.series, series_path(series_dir, key))
                row = {KEY: key, **constants, **spec.params, "t_end": spec.t_end,
                       "record_interval": spec.record_interval, "fmu_sha256": image.sha256,
                       **outcome.row}
                results.append(row)
                report.executed += 1
        finally:  # the rows' file closed, the sweep ended or interrupted
            results.release()

    report.results = results.close(unique, done=finished)
    return report


def series_path(series_dir: str, key: str) -> str:
    return os.path.join(series_dir, f"{key}.csv")


def segments_path(series_dir: str, key: str) -> str:
    """Each segment's charge at the end of the run (from an FMI 3.0 FMU)."""
    return os.path.join(series_dir, f"{key}.segments.csv")


SERIES_FLOAT_FORMAT = "%.10g"


def write_series(series, path: str) -> None:
    """A run's series (a DataFrame, or a dict of equally long columns) as its CSV file."""
    tmp = path + ".tmp"
    text = table_csv(series, SERIES_FLOAT_FORMAT)
    if text is None:
        pd.DataFrame(series).to_csv(tmp, index=False, float_format=SERIES_FLOAT_FORMAT)
    else:
        with open(tmp, "w") as f:
            f.write(text)
    os.replace(tmp, path)


def read_series(series_dir: str, key: str) -> pd.DataFrame:
    return pd.read_csv(series_path(series_dir, key))


def read_many_series(series_dir: str, keys: list[str]) -> tuple[pd.DataFrame, list[int]]:
    """The series of `keys` as one table, their rows in the keys' order, and each one's number
    of rows: pd.concat of read_series's (ignore_index), to the bit, where every file has the
    same header (the files' text parsed in one call: a parse a file cost a line's grain more
    CPU than its flights, docs/line.md "Benchmark"); one by one where they differ."""
    header, bodies, lengths = None, [], []
    for key in keys:
        with open(series_path(series_dir, key), newline="") as f:
            text = f.read()
        head, _, body = text.partition("\n")
        if header is None:
            header = head
        if head != header or "\r" in text or '"' in body:  # not plain lines of numbers
            frames = [read_series(series_dir, k) for k in keys]
            return pd.concat(frames, ignore_index=True), [len(f) for f in frames]
        if body and not body.endswith("\n"):
            body += "\n"
        bodies.append(body)
        lengths.append(body.count("\n"))
    frame = pd.read_csv(io.StringIO(header + "\n" + "".join(bodies)))
    return frame, lengths


def read_segments(series_dir: str, key: str) -> pd.DataFrame | None:
    path = segments_path(series_dir, key)
    return pd.read_csv(path) if os.path.exists(path) else None
