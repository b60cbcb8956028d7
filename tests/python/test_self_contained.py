"""The repository stands on its own: no file in it refers to a path outside it.

A clone has nothing but its own files, so every reference a file makes must resolve inside
the repository: relative paths that climb out of it (`../x` from the top), absolute paths
into a machine's own folders (home directories, work folders), markdown links that lead
nowhere, and the names of the specification documents the project was developed from,
which live outside it (the project's own statement of the model is docs/model.md).
"""

import os
import re
import subprocess

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Absolute paths that exist on every machine the project builds on.
SYSTEM_PREFIXES = ("usr", "bin", "sbin", "lib", "lib64", "etc", "dev", "proc", "sys", "opt", "var")

# A relative path that climbs: ../ at least once, then a path.
CLIMBING = re.compile(r"(?<![\w.])((?:\.\./)+[\w.\-/]*)")
# An absolute path of two or more components, not part of a URL, a ratio or a longer path.
ABSOLUTE = re.compile(r"(?<![\w.:/~\-\])}>*])/((?:[\w.\-]+/)+[\w.\-]*)")
# A markdown link or image: [text](target) or ![alt](target).
LINK = re.compile(r"\]\(([^)\s]+)\)")
# The external specification's file names (assembled so that this file does not match).
EXTERNAL_NAMES = re.compile(r"\b(" + "MODEL" + r"\.md|shared/" + "seed" + r"|ireland2012_model)\b")


def repository_files() -> list[str]:
    """The files a clone has: git's list of tracked and not ignored files."""
    out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                         cwd=ROOT, capture_output=True, text=True, check=True).stdout
    return [f for f in out.splitlines() if os.path.isfile(os.path.join(ROOT, f))]


def text_of(path: str) -> str | None:
    with open(os.path.join(ROOT, path), "rb") as f:
        data = f.read()
    if b"\0" in data:
        return None  # binary (figures)
    return data.decode("utf-8", errors="replace")


def inside(path: str) -> bool:
    real = os.path.realpath(path)
    return real == ROOT or real.startswith(ROOT + os.sep)


def problems_in(name: str, text: str) -> list[str]:
    here = os.path.dirname(os.path.join(ROOT, name))
    found = []
    for lineno, line in enumerate(text.splitlines(), 1):
        where = f"{name}:{lineno}"
        for m in CLIMBING.finditer(line):
            target = m.group(1)
            # resolved from the file's folder (a link, an include) or from the top (a command)
            candidates = [os.path.join(here, target), os.path.join(ROOT, target)]
            if not any(inside(c) and os.path.exists(c.rstrip("/") or "/") for c in candidates):
                found.append(f"{where}: {target!r} leads outside the repository or nowhere")
        for m in ABSOLUTE.finditer(line):
            first = m.group(1).split("/", 1)[0]
            if first not in SYSTEM_PREFIXES:
                found.append(f"{where}: absolute path /{m.group(1)!s}")
        if name.endswith(".md"):
            for m in LINK.finditer(line):
                target = m.group(1).split("#", 1)[0]
                if not target or re.match(r"^[a-z]+:", target):
                    continue  # an anchor in the same file, or a URL
                path = os.path.join(here, target)
                if not (inside(path) and os.path.exists(path)):
                    found.append(f"{where}: link to {target!r}, which is not in the repository")
        if EXTERNAL_NAMES.search(line):
            found.append(f"{where}: names a document outside the repository: {line.strip()[:120]}")
    return found


# Not scanned: this file (its examples are such references on purpose) and .gitignore (its
# leading / anchors a pattern at the top of the repository).
NOT_SCANNED = {os.path.relpath(os.path.abspath(__file__), ROOT), ".gitignore"}


def test_no_file_refers_to_a_path_outside_the_repository():
    files = repository_files()
    assert "docs/model.md" in files and "README.md" in files
    problems = []
    for name in sorted(set(files) - NOT_SCANNED):
        text = text_of(name)
        if text is not None:
            problems += problems_in(name, text)
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("line, expected", [
    ("see ../shared/spec.md", "leads outside"),
    ("[the model](../../elsewhere/model.md)", "not in the repository"),
    ("[the model](docs/nowhere.md)", "not in the repository"),
    ("cd /work/project && make", "absolute path"),
    ("open /home/someone/notes.txt", "absolute path"),
    ("the spec (" + "MODEL" + ".md §3)", "outside the repository"),
])
def test_the_check_catches_each_kind_of_reference(line, expected):
    """(So that a clean result above means something.)"""
    problems = problems_in("README.md", line)
    assert any(expected in p for p in problems), problems


@pytest.mark.parametrize("name, line", [
    ("README.md", "[the model](docs/model.md), [§3](docs/model.md#3-forces)"),
    ("fmu/README.md", "`../modelDescription/` holds the reviewed copies"),
    ("README.md", "PYTHON=/usr/bin/python3; https://example.org/a/b; m/s; 1/2 of it"),
    ("README.md", "cite the project's docs/model.md as model.md §3"),
])
def test_references_inside_the_repository_pass(name, line):
    assert problems_in(name, line) == []
