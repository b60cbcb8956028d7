"""An output folder (--out, out=): every command writes its results into one, and a folder
holds the results of one command and one set-up.

`claim(out, kind, setup, fresh)` is entered before any cluster starts or any run is made.
It takes the folder's lock, then reads the folder's record, `tribo.json` (which command
wrote it, for which set-up: what gives the rows their meaning without being a column of
them, and the FMU's SHA-256):

- a missing or empty folder is made and recorded: a new start;
- the same command and set-up: the results are resumed (only the missing runs run);
- the same command and set-up with another FMU (a rebuilt one): the earlier results move
  into <out>/backup-<n>/ and the folder starts over, said in one line (its runs would not
  be this FMU's);
- the same command with another set-up: refused in one line naming what differs, or with
  `fresh`, moved into <out>/backup-<n>/ like the above;
- another command's results, or files without a record: refused in one line, `fresh` or
  not (nothing of another command's or of the user's is moved); files of this command
  without a record move with `fresh`.

The lock is an advisory lock on <out>/.tribo.lock held for the whole command (released
when the process ends, however it ends): a second command into the same folder is refused
in one line instead of running the same runs again.
"""

import contextlib
import datetime
import fnmatch
import json
import os

from ..fmu.names import format_number

RECORD = "tribo.json"
LOCK = ".tribo.lock"
BACKUP_PREFIX = "backup-"
# what each kind of command writes into its folder (so that its files without a record are
# recognised as its own)
OWN_FILES = {
    "study": ["study.md", "study_runs.csv", "transition_points.csv", "*.png", "runs"],
    "sweep": ["results.csv", "results.png", "results.backup-*.csv", "series"],
    "population": ["particles.csv", "particles.backup-*.csv", "summary.csv", "population.png",
                   "population.json"],
    "impact map": ["episodes.csv", "episodes.backup-*.csv", "impact_map.csv", "impact_map.json",
                   "impact_map.png"],
    "line": ["particles.csv", "particles.backup-*.csv", "landings", "landings.csv", "line.csv",
             "bins.csv", "line.png", "line.json"],
    "calibration": ["fit.csv", "points.csv", "profile.csv", "materials.toml",
                    "calibration.png", "calibration.json"],
    "dem": ["particles.csv", "impacts.csv", "summary.csv", "population.png", "population.json",
            "liggghts"],
}
COMMANDS = {"study": "tribo study", "sweep": "tribo sweep", "population": "tribo population",
            "impact map": "tribo impact-map", "line": "tribo line",
            "calibration": "tribo calibrate", "dem": "tribo dem"}


class FolderError(ValueError):
    """An output folder that cannot be used (the message, one line, says why and what to do)."""


class Claim:
    """A claimed folder: `path`, and `backup` (where earlier results went, or None) with
    `note` (the line that says so)."""

    def __init__(self, path: str):
        self.path = path
        self.backup = None
        self.note = None


@contextlib.contextmanager
def claim(out: str, kind: str, setup: dict, fmu_sha256: str, fresh: bool = False):
    """Claim the folder `out` for a command of `kind` ("study", "sweep", "population",
    "impact map", "line", "calibration") and its `setup` (plain JSON values), run with the FMU of that SHA-256
    (see the module's text); yields a Claim, and holds the lock until the block ends."""
    if kind not in OWN_FILES:
        raise ValueError(f"kind {kind!r}: one of {', '.join(OWN_FILES)}")
    if os.path.exists(out) and not os.path.isdir(out):
        raise FolderError(f"--out {out}: a file, not a folder (the results go into a folder)")
    try:
        os.makedirs(out, exist_ok=True)
    except OSError as e:
        raise FolderError(f"cannot write into {out}: {e.strerror or e}") from None
    with _locked(out, kind):
        record = _read_record(out)
        entries = [e for e in os.listdir(out) if e not in (LOCK, RECORD) and not e.startswith(BACKUP_PREFIX)]
        setup = json.loads(json.dumps(setup))  # as it reads back from the file
        result = Claim(out)
        if record is None and entries:
            others = [e for e in entries if not _own(kind, e)]
            if others:
                raise FolderError(f"{out} holds files that no tribo command recorded ({_few(others)}): "
                                  f"give another --out, or an empty folder")
            if not fresh:
                raise FolderError(f"{out} holds {kind} results without a record of their set-up: "
                                  f"give --fresh to start over (they are "
                                  f"kept in {os.path.join(out, BACKUP_PREFIX)}<n>/), or another --out")
            _back_up(out, result, "the earlier results, without a record of their set-up,")
        elif record is not None:
            if record.get("kind") != kind:
                theirs = record.get("kind", "unknown")
                raise FolderError(f"{out} holds the results of {COMMANDS.get(theirs, theirs)} "
                                  f"(a {theirs}), not of {COMMANDS[kind]}: give another --out")
            if record.get("setup") != setup:
                if not fresh:
                    raise FolderError(f"{out} holds a {kind} of another set-up "
                                      f"({_differences(record.get('setup') or {}, setup)}): give "
                                      f"another --out, or --fresh to start over (the earlier "
                                      f"results are kept in {os.path.join(out, BACKUP_PREFIX)}<n>/)")
                _back_up(out, result, "the earlier results")
            elif record.get("fmu_sha256") != fmu_sha256:
                _back_up(out, result, "the FMU has changed since this folder was written: its results")
            elif fresh:
                _back_up(out, result, "the earlier results")
        _write_record(out, kind, setup, fmu_sha256)
        yield result


def _own(kind: str, entry: str) -> bool:
    return any(fnmatch.fnmatch(entry, pattern) for pattern in OWN_FILES[kind])


def _few(names, n: int = 3) -> str:
    names = sorted(names)
    return ", ".join(names[:n]) + (f" and {len(names) - n} more" if len(names) > n else "")


def _differences(before: dict, now: dict) -> str:
    """What differs between two set-ups, in words: "seed 1 -> 2; particle PE -> PP"."""
    flat_before, flat_now = _flatten(before), _flatten(now)
    parts = []
    for name in list(dict.fromkeys(list(flat_before) + list(flat_now))):
        a, b = flat_before.get(name, "unset"), flat_now.get(name, "unset")
        if a != b:
            parts.append(f"{name} {_text(a)} -> {_text(b)}")
    return "; ".join(parts[:3]) + (f"; {len(parts) - 3} more" if len(parts) > 3 else "")


def _flatten(d: dict, prefix: str = "") -> dict:
    out = {}
    for k, v in d.items():
        if isinstance(v, dict):
            out.update(_flatten(v, f"{prefix}{k}."))
        else:
            out[f"{prefix}{k}"] = v
    return out


def _text(v) -> str:
    if isinstance(v, list):
        return "[" + ", ".join(_text(x) for x in v) + "]"
    return format_number(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else str(v)


def _back_up(out: str, claim_: Claim, what: str) -> None:
    """Move everything in the folder but the lock and earlier backups into backup-<n>/."""
    n = 1
    while os.path.exists(os.path.join(out, f"{BACKUP_PREFIX}{n}")):
        n += 1
    target = os.path.join(out, f"{BACKUP_PREFIX}{n}")
    os.makedirs(target)
    for entry in os.listdir(out):
        if entry != LOCK and not entry.startswith(BACKUP_PREFIX):
            os.replace(os.path.join(out, entry), os.path.join(target, entry))
    claim_.backup = target
    claim_.note = f"{what} are kept in {target}"


def _read_record(out: str):
    path = os.path.join(out, RECORD)
    if not os.path.exists(path):
        return None
    try:
        with open(path, encoding="utf-8") as f:
            record = json.load(f)
    except (OSError, ValueError) as e:
        raise FolderError(f"{path} cannot be read ({e}): give another --out") from None
    if not isinstance(record, dict):
        raise FolderError(f"{path} is not a record of a tribo command: give another --out")
    return record


def _write_record(out: str, kind: str, setup: dict, fmu_sha256: str) -> None:
    path = os.path.join(out, RECORD)
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump({"kind": kind, "command": COMMANDS[kind], "setup": setup,
                   "fmu_sha256": fmu_sha256}, f, indent=2)
        f.write("\n")
    os.replace(tmp, path)


@contextlib.contextmanager
def _locked(out: str, kind: str):
    path = os.path.join(out, LOCK)
    made = not os.path.exists(path)
    try:
        f = open(path, "a+", encoding="utf-8")
    except OSError as e:  # a read-only folder, a lock that is not a file
        raise FolderError(f"cannot write into {out}: {e.strerror or e}") from None
    try:
        if not _try_lock(f):
            f.seek(0)
            holder = f.read().strip() or "another process"
            raise FolderError(f"{out} is in use by {holder}: wait for it to finish, or give "
                              f"another --out")
        f.seek(0)
        f.truncate()
        started = datetime.datetime.now().strftime("%Y-%m-%d %H:%M:%S")
        f.write(f"{COMMANDS[kind]} (process {os.getpid()}, since {started})\n")
        f.flush()
        try:
            yield
        except FolderError:
            if made:  # a folder refused keeps nothing of this command (removed while held)
                os.unlink(path)
            raise
        finally:
            if not f.closed and os.path.exists(path):
                f.seek(0)
                f.truncate()
                f.flush()
            _unlock(f)
    finally:
        f.close()


try:
    import fcntl
except ImportError:  # Windows
    fcntl = None
    import msvcrt


def _try_lock(f) -> bool:
    try:
        if fcntl is not None:
            fcntl.flock(f.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        else:
            f.seek(0)
            msvcrt.locking(f.fileno(), msvcrt.LK_NBLCK, 1)
    except OSError:
        return False
    return True


def _unlock(f) -> None:
    if fcntl is not None:
        fcntl.flock(f.fileno(), fcntl.LOCK_UN)
    else:
        f.seek(0)
        msvcrt.locking(f.fileno(), msvcrt.LK_UNLCK, 1)
