"""The results file of a sweep: a CSV with one row per finished run, keyed by the run's
key (specs.run_key).

Rows are appended (and flushed to disk) as runs finish, so an interrupted sweep loses
at most the runs that were in flight; a row cut short by the interruption is dropped
when the file is opened again. Starting a file afresh never deletes it: the old file is
renamed to <name>.backup-<n>.csv first. `rewrite_in_order` puts the rows in a given order (the
sweep does so when it completes). Floats are written in their shortest round-trip form, which
pandas (3.x) reads back exactly: numbers survive the file bit for bit.
"""

import os

import pandas as pd

KEY = "key"
_TEXT_COLUMNS = {KEY: str, "fmu_sha256": str}


def read_results(path: str) -> pd.DataFrame:
    """A results file as a DataFrame (what a user does with pandas.read_csv, with exact floats)."""
    return pd.read_csv(path, dtype=_TEXT_COLUMNS)


class ResultsFile:
    """A results CSV with a fixed header (`columns`, the first of which is KEY)."""

    def __init__(self, path: str, columns: list[str], fresh: bool = False):
        if columns[0] != KEY:
            raise ValueError(f"the first column must be {KEY!r}")
        # absolute: FMU runs in other threads change the working directory for a moment
        # (fmu/instance.py)
        self.path = os.path.abspath(path)
        self.columns = list(columns)
        self.backup = None  # where fresh=True moved an earlier file
        if fresh and os.path.exists(path):
            self.backup = backup_path(path)
            os.replace(path, self.backup)
        self._open_or_create()

    def _open_or_create(self):
        header = ",".join(self.columns) + "\n"
        if os.path.exists(self.path):
            with open(self.path, "rb") as f:
                data = f.read()
            # a run killed mid-write leaves a last line without its newline: drop it
            complete = data[: data.rfind(b"\n") + 1]
            if complete:
                found = complete.split(b"\n", 1)[0].decode().split(",")
                if found != self.columns:
                    raise ValueError(f"{self.path} holds runs with other columns ({_difference(found, self.columns)}): "
                                     f"write to another file, or start this one afresh (--fresh; the "
                                     f"old file is kept as a backup)")
                if len(complete) != len(data):
                    with open(self.path, "wb") as f:
                        f.write(complete)
                return
        os.makedirs(os.path.dirname(os.path.abspath(self.path)), exist_ok=True)
        with open(self.path, "w") as f:
            f.write(header)

    def read(self) -> pd.DataFrame:
        return read_results(self.path).drop_duplicates(KEY, keep="first")

    def finished_keys(self) -> set[str]:
        return set(self.read()[KEY])

    def append(self, row: dict) -> None:
        if set(row) != set(self.columns):
            missing, extra = set(self.columns) - set(row), set(row) - set(self.columns)
            raise ValueError(f"row does not match the header: missing {sorted(missing)}, "
                             f"extra {sorted(extra)}")
        line = pd.DataFrame([row], columns=self.columns).to_csv(header=False, index=False)
        with open(self.path, "a") as f:
            f.write(line)
            f.flush()
            os.fsync(f.fileno())

    def rewrite_in_order(self, keys: list[str]) -> None:
        """Rows of `keys` first, in that order, then any others as they were."""
        df = self.read()
        rank = {k: i for i, k in enumerate(keys)}
        df = df.assign(_rank=df[KEY].map(rank).fillna(len(rank))).sort_values("_rank", kind="stable")
        tmp = self.path + ".tmp"
        df.drop(columns="_rank").to_csv(tmp, index=False)
        os.replace(tmp, self.path)


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
