"""A file a user names as input (a materials file, a calibration's CSV, measured feed values):
read whole, with the reason it cannot be in one line: missing, a folder, not a regular
file (a device such as /dev/zero, a pipe), or larger than such a file can be. A device or
a pipe is refused before anything is read: /dev/zero would be read until memory runs out."""

import os
import stat

# An input file is a table of at most some thousands of rows; 64 MiB holds a million rows
# of a calibration's columns and bounds what a mistaken path (a disk image, a log) costs.
MAX_INPUT_BYTES = 64 * 2**20


def input_problem(path: str, limit: int = MAX_INPUT_BYTES) -> str | None:
    """Why the file at `path` cannot be read as input, in words; None where it can."""
    try:
        info = os.stat(path)
    except FileNotFoundError:
        return "no such file"
    except OSError as e:
        return f"cannot read it: {e.strerror or e}"
    if stat.S_ISDIR(info.st_mode):
        return "a folder, not a file"
    if not stat.S_ISREG(info.st_mode):
        return "not a regular file (a device or a pipe): give the path of a file"
    if info.st_size > limit:
        return f"{info.st_size / 2**20:.0f} MiB, above the {limit / 2**20:.0f} MiB an input file may hold"
    return None


def read_input(path: str, error, what: str, limit: int = MAX_INPUT_BYTES) -> bytes:
    """The bytes of the input file `path` (at most `limit`), or `error(line)` raised with
    the line "<what> <path>: <reason>"."""
    problem = input_problem(path, limit)
    if problem is None:
        try:
            with open(path, "rb") as f:
                data = f.read(limit + 1)  # a file that grew since its size was read
        except OSError as e:
            problem = f"cannot read it: {e.strerror or e}"
        else:
            if len(data) <= limit:
                return data
            problem = f"above the {limit / 2**20:.0f} MiB an input file may hold"
    raise error(f"{what} {path}: {problem}")


def shown(text, limit: int = 60) -> str:
    """A text of the user's as a message shows it: at most `limit` characters (a column
    name of 100 MB would be a message of 100 MB)."""
    text = str(text)
    return text if len(text) <= limit else f"{text[:limit]}... ({len(text)} characters)"
