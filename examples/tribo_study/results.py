"""The results file of a sweep: a CSV with one row per finished run, keyed by the run's
key (specs.run_key).

Rows are appended (and flushed to disk) as runs finish, so an interrupted sweep loses
at most the runs that were in flight; a row cut short by the interruption is dropped
when the file is opened again. `rewrite_in_order` puts the rows in a given order (the
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
        self.path = path
        self.columns = list(columns)
        if fresh and os.path.exists(path):
            os.remove(path)
        self._open_or_create()

    def _open_or_create(self):
        header = ",".join(self.columns) + "\n"
        if os.path.exists(self.path):
            with open(self.path, "rb") as f:
                data = f.read()
            # a run killed mid-write leaves a last line without its newline: drop it
            complete = data[: data.rfind(b"\n") + 1]
            if complete:
                found = complete.split(b"\n", 1)[0].decode()
                if found.split(",") != self.columns:
                    raise ValueError(
                        f"{self.path} holds the results of other runs (its columns differ); "
                        f"start afresh (--fresh) or write to another file")
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
