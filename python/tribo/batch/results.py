"""The results file of a sweep: a CSV with one row per finished run, keyed by the run's
key (specs.run_key).

Rows are appended (handed to the system at once, forced to the disk at least every
second) as runs finish, so an interrupted sweep loses at most the runs that were in
flight. The file is read once, when it is opened: a last
line cut short by an interruption is dropped, and so is any row that does not read back
as written (not UTF-8, another number of fields, a number column holding text such as
`x.y01`): nothing that cannot be read back is kept as a result. Such rows are moved out
(the file as it was is kept as <name>.backup-<n>.csv, said in `note`), and their runs
run again. A header other than the runs' is refused in one line (`ResultsError`).

Starting a file afresh never deletes it: the old file is renamed to <name>.backup-<n>.csv
first. `close(keys)` returns the rows of the given keys, in that order, and puts the file
in that order when it holds exactly those runs. Floats are written in their shortest
round-trip form, which pandas (3.x) reads back exactly: numbers survive the file bit for
bit.
"""

import csv
import io
import os
import time

import numpy as np
import pandas as pd

KEY = "key"
# appended rows are handed to the system at once (a sweep that is interrupted keeps them),
# and forced to the disk at most this often and at the end (a machine that goes down loses
# the last second's rows): a sync a row cost about as much wall time as a grain's run
SYNC_INTERVAL_S = 1.0
_TEXT_COLUMNS = {KEY: str, "fmu_sha256": str}


class ResultsError(ValueError):
    """A results file that cannot be resumed (the message, one line, says why and what to do)."""


def read_results(path: str) -> pd.DataFrame:
    """A results file as a DataFrame (what a user does with pandas.read_csv, with exact floats)."""
    return pd.read_csv(path, dtype=_TEXT_COLUMNS)


def count_rows(path: str, keys=None) -> int:
    """How many rows of the results file (of `keys`, if given) read back; 0 for a file
    that is missing or cannot be read."""
    try:
        found = read_results(path)[KEY]
    except (OSError, ValueError, KeyError, UnicodeDecodeError, pd.errors.ParserError):
        return 0
    return len(set(found) & set(keys)) if keys is not None else found.nunique()


class ResultsFile:
    """A results CSV with a fixed header (`columns`, the first of which is KEY); the
    columns in `text_columns` (and KEY, fmu_sha256) hold text, every other one a number
    or nothing (NaN)."""

    def __init__(self, path: str, columns: list[str], fresh: bool = False, text_columns=()):
        if columns[0] != KEY:
            raise ValueError(f"the first column must be {KEY!r}")
        # absolute: FMU runs in other threads change the working directory for a moment
        # (fmu/instance.py)
        self.path = os.path.abspath(path)
        self.columns = list(columns)
        self.numeric = [i for i, c in enumerate(self.columns)
                        if c not in _TEXT_COLUMNS and c not in set(text_columns)]
        self.backup = None  # where fresh=True, or rows that do not read back, moved the file
        self.note = None  # the line that says rows were moved out
        if fresh and os.path.exists(self.path):
            self.backup = backup_path(self.path)
            os.replace(self.path, self.backup)
        self.rows = self._open_or_create()  # the finished runs' rows, read once
        self._column_set = frozenset(self.columns)
        self._appending = None  # the file open for appending rows (append, release)
        self._synced = time.monotonic()  # when the rows appended were last forced to disk

    def _open_or_create(self) -> pd.DataFrame:
        data = b""
        if os.path.exists(self.path):
            with open(self.path, "rb") as f:
                data = f.read()
        lines = data.split(b"\n")
        tail = lines.pop()  # after the last newline: empty, or a row cut short
        if not lines:  # a new file, or not even its header was written in full
            os.makedirs(os.path.dirname(self.path), exist_ok=True)
            with open(self.path, "w") as f:
                f.write(",".join(self.columns) + "\n")
            return read_results(self.path)
        self._check_header(lines[0])
        bad = [n for n, line in enumerate(lines[1:], 2) if not self._readable(line)]
        if bad:
            self.backup = backup_path(self.path)
            os.replace(self.path, self.backup)
            self.note = (f"{self.path}: {len(bad)} row(s) that do not read back as numbers "
                         f"(line {', '.join(map(str, bad[:5]))}{', ...' if len(bad) > 5 else ''}) "
                         f"left out, their runs run again (the file as it was: {self.backup})")
        if bad or tail:
            keep = [line for n, line in enumerate(lines, 1) if n not in set(bad)]
            tmp = self.path + ".tmp"
            with open(tmp, "wb") as f:
                f.write(b"".join(line + b"\n" for line in keep))
            os.replace(tmp, self.path)
        return read_results(self.path).drop_duplicates(KEY, keep="first")

    def _check_header(self, line: bytes) -> None:
        try:
            found = line.decode().split(",")
        except UnicodeDecodeError:
            found = None
        if found != self.columns:
            what = _difference(found, self.columns) if found else "a header that is not text"
            raise ResultsError(f"{self.path} holds runs with other columns ({what}): write to "
                               f"another folder, or start this one afresh (--fresh, fresh=True; "
                               f"the old file is kept as a backup)")

    def _readable(self, line: bytes) -> bool:
        """Whether a row reads back: text, the header's number of fields, a key, numbers
        (or nothing) where numbers go."""
        try:
            fields = next(csv.reader([line.decode()]))
        except (UnicodeDecodeError, StopIteration, csv.Error):
            return False
        if len(fields) != len(self.columns) or not fields[0]:
            return False
        for i in self.numeric:
            if fields[i]:
                try:
                    float(fields[i])
                except ValueError:
                    return False
        return True

    @property
    def finished(self) -> set[str]:
        """The keys of the rows found when the file was opened."""
        return set(self.rows[KEY])

    def append(self, row: dict) -> None:
        """The row at the end of the file, handed to the system at once (the file stays open
        for the next row, in append mode: each write goes to the end, wherever another
        process's went; closed by `release` and `close`)."""
        if row.keys() != self._column_set:
            missing, extra = set(self.columns) - set(row), set(row) - set(self.columns)
            raise ValueError(f"row does not match the header: missing {sorted(missing)}, "
                             f"extra {sorted(extra)}")
        line = csv_line([row[c] for c in self.columns])
        f = self._appending
        if f is None:
            f = self._appending = open(self.path, "a")
        f.write(line)
        f.flush()
        if time.monotonic() - self._synced >= SYNC_INTERVAL_S:
            os.fsync(f.fileno())
            self._synced = time.monotonic()

    def release(self) -> None:
        """Close the file the rows were appended to (their last ones forced to the disk)."""
        f, self._appending = self._appending, None
        if f is not None:
            with f:
                os.fsync(f.fileno())

    def close(self, keys: list[str], done=None) -> pd.DataFrame:
        """The rows of `keys` that are in the file (and `done(key)`, if given: e.g. their
        series are on disk too), in that order. A file that holds exactly those runs, all
        done, is rewritten in that order (a file several sweeps share keeps the order its
        rows came in)."""
        self.release()
        with open(self.path, "a") as f:  # the rows since the last sync
            os.fsync(f.fileno())
        table = read_results(self.path).drop_duplicates(KEY, keep="first")
        found = set(table[KEY])
        finished = [k for k in keys if k in found and (done is None or done(k))]
        if found == set(keys) and len(finished) == len(keys):
            rank = {k: i for i, k in enumerate(keys)}
            table = table.iloc[table[KEY].map(rank).argsort(kind="stable")]
            tmp = self.path + ".tmp"
            table.to_csv(tmp, index=False)
            os.replace(tmp, self.path)
            table = read_results(self.path)
        return table.set_index(KEY).loc[finished].reset_index()


def csv_line(values: list) -> str:
    """One row as pandas writes a one-row DataFrame of these values (to_csv, no header, no
    index): a float in its shortest round-trip form, NaN and None as nothing, text quoted
    where it must be. Without building the DataFrame, which cost a particle's row more CPU
    than the package's own part of its run (docs/populations.md, "Benchmark"); values of
    other types go through pandas."""
    fields = []
    for v in values:
        kind = type(v)  # the common types first, as the branches below write them
        if kind is float:
            fields.append("" if v != v else repr(v))
            continue
        if kind is int:
            fields.append(str(v))
            continue
        if isinstance(v, str):
            fields.append(v)
        elif isinstance(v, (float, np.floating)) and not isinstance(v, np.float16 | np.float32):
            fields.append("" if v != v else repr(float(v)))
        elif isinstance(v, (bool, np.bool_)):
            fields.append(str(bool(v)))
        elif isinstance(v, (int, np.integer)):
            fields.append(str(int(v)))
        elif v is None:
            fields.append("")
        else:
            return pd.DataFrame([values]).to_csv(header=False, index=False)
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerow(fields)
    return out.getvalue()


def table_csv(columns, float_format: str) -> str | None:
    """pd.DataFrame(columns).to_csv(index=False, float_format=float_format)'s text, the same
    bytes, for `columns` (a DataFrame, or a dict of equally long arrays) of float64 and
    int64 columns with text names (None for others: pandas writes them): a float formatted
    by float_format, NaN as nothing. Without pandas' writer or a DataFrame, which cost a line's
    grain more CPU than its flights (docs/line.md, "Benchmark")."""
    names = list(columns)
    if not all(isinstance(name, str) for name in names):
        return None
    fields = []
    for name in names:
        values = np.asarray(columns[name])
        if values.ndim != 1:
            return None
        if values.dtype == np.float64:
            fields.append(["" if v != v else float_format % v for v in values.tolist()])
        elif values.dtype == np.int64:
            fields.append([str(v) for v in values.tolist()])
        else:
            return None
    if len({len(f) for f in fields}) > 1:
        return None
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerow(names)
    out.writelines(",".join(row) + "\n" for row in zip(*fields))
    return out.getvalue()


def backup_path(path: str) -> str:
    """<stem>.backup-<n><ext>, the first n not taken."""
    stem, ext = os.path.splitext(path)
    n = 1
    while os.path.exists(f"{stem}.backup-{n}{ext}"):
        n += 1
    return f"{stem}.backup-{n}{ext}"


def _difference(found: list[str], wanted: list[str]) -> str:
    only_file = [c for c in found if c not in wanted]
    only_new = [c for c in wanted if c not in found]
    parts = []
    if only_file:
        parts.append(f"the file has {', '.join(only_file)}")
    if only_new:
        parts.append(f"these runs have {', '.join(only_new)}")
    return "; ".join(parts) or "in another order"
