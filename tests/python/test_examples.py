"""Every example runs as written: each ```python block of README.md and of the user guide's
pages (docs/README.md's table), saved as a script and run in a fresh folder with the venv's
Python; each example line of the subcommands' --help; and each command line of `tribo` that
README.md and docs/ show (in code spans and blocks), which use the subcommands, not the
aliases.

The blocks run as they are: they are small on purpose. The command examples show sizes a
user would run (1000 particles, tau to 1000, an existing cluster); they run here at a small
size, by the substitutions in `shrink` (each one named there), and the cluster examples on
a scheduler and a worker started for the test."""

import glob

import os
import re
import shlex
import shutil
import socket
import subprocess
import sys

import pytest

from study_support import PYTHON, command
from tribo_fmu import ROOT

SUBCOMMANDS = ["study", "sweep", "population", "grain", "impact-map", "line", "calibrate", "dem"]
ALIASES = ["tribo-study", "tribo-sweep", "tribo-population", "tribo-impact-map", "tribo-line"]


def guide_pages() -> list[str]:
    """README.md and the pages docs/README.md's table lists (paths from the checkout)."""
    with open(os.path.join(ROOT, "docs", "README.md"), encoding="utf-8") as f:
        table = [line for line in f if line.startswith("| [")]
    pages = {os.path.join("docs", m) for line in table for m in re.findall(r"\]\(([\w./-]+\.md)\)", line)}
    return ["README.md"] + sorted(pages)


def python_blocks() -> list[tuple[str, int, str]]:
    blocks = []
    for page in guide_pages():
        with open(os.path.join(ROOT, page), encoding="utf-8") as f:
            text = f.read()
        for i, code in enumerate(re.findall(r"^```python\n(.*?)^```", text, re.S | re.M), 1):
            blocks.append((page, i, code))
    return blocks


BLOCKS = python_blocks()


def test_the_guide_has_its_pages_and_examples():
    pages = guide_pages()
    assert {"README.md", "docs/si.md", "docs/populations.md", "docs/sweeps.md", "docs/fmu.md",
            "docs/integrators.md", "docs/platforms.md"} <= set(pages)
    assert all(os.path.exists(os.path.join(ROOT, p)) for p in pages)
    with_code = {page for page, _, _ in BLOCKS}
    assert {"README.md", "docs/si.md", "docs/populations.md", "docs/sweeps.md", "docs/fmu.md"} <= with_code
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as f:
        assert len(f.read().splitlines()) <= 150  # a README of one screen


@pytest.mark.parametrize("page, index, code", BLOCKS, ids=[f"{p}#{i}" for p, i, _ in BLOCKS])
def test_each_python_block_runs_as_a_script(tmp_path, page, index, code):
    script = tmp_path / "example.py"
    script.write_text(code)
    done = subprocess.run([PYTHON, str(script)], cwd=tmp_path, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, f"{page}, block {index}:\n{done.stderr[-3000:]}"
    assert "Traceback" not in done.stderr and done.stdout.strip(), done.stderr[-3000:]


def help_examples(sub: str) -> list[str]:
    """The example command lines of a subcommand's --help (indented, starting with
    `tribo <sub>`; a trailing backslash continues a line)."""
    text = subprocess.run([command("tribo"), sub, "--help"], capture_output=True, text=True,
                          check=True, timeout=60).stdout
    examples, current = [], None
    for line in text.splitlines():
        stripped = line.strip()
        if current is not None:
            current += " " + stripped.rstrip("\\").strip()
            if not stripped.endswith("\\"):
                examples.append(current)
                current = None
        elif line.startswith("    ") and stripped.startswith(f"tribo {sub} "):
            if stripped.endswith("\\"):
                current = stripped.rstrip("\\").strip()
            else:
                examples.append(stripped)
    return examples


def documents() -> list[str]:
    """README.md and every page under docs/ (paths from the checkout)."""
    pages = glob.glob(os.path.join(ROOT, "docs", "**", "*.md"), recursive=True)
    return ["README.md"] + sorted(os.path.relpath(p, ROOT) for p in pages)


# a command line in a code span (it may wrap onto the next line), in a fenced block or in an
# indented block, by the venv's path or not: `tribo <sub> ...` (or an alias, which the docs
# must not use)
SPAN = re.compile(r"`(?:\.venv/bin/)?(tribo[ -][a-z][^`]*)`")
FENCED = re.compile(r"^```(\w*)\n(.*?)^```", re.S | re.M)
FENCED_LINE = re.compile(r"^\s*(?:\.venv/bin/)?(tribo[ -][a-z].*)$")
INDENTED_LINE = re.compile(r"^    (?:\.venv/bin/)?(tribo[ -][a-z].*)$")


def documented_commands() -> list[tuple[str, str]]:
    """(page, command line) of each command of the package README.md and docs/ show."""
    found = set()
    for page in documents():
        with open(os.path.join(ROOT, page), encoding="utf-8") as f:
            text = f.read()
        lines = [m.group(1) for m in SPAN.finditer(text)]
        for language, block in FENCED.findall(text):
            if language in ("", "sh", "bash", "console"):
                lines += [m.group(1) for m in map(FENCED_LINE.match, block.splitlines()) if m]
        lines += [m.group(1) for m in map(INDENTED_LINE.match, text.splitlines()) if m]
        for line in lines:
            words = shlex.split(line, comments=True)
            if len(words) > 1 and (words[0] in ALIASES or (words[0] == "tribo"
                                                           and words[1] in SUBCOMMANDS)):
                found.add((page, " ".join(words)))
    return sorted(found)


DOCUMENTED = documented_commands()


def test_the_docs_show_the_subcommands_not_the_aliases():
    assert {line.split()[1] for _, line in DOCUMENTED if line.startswith("tribo ")} >= \
        set(SUBCOMMANDS)
    aliases = [f"{page}: {line}" for page, line in DOCUMENTED if line.split()[0] in ALIASES]
    assert not aliases, aliases


def test_the_documented_commands_write_under_out():
    # the 10,000-grain example wrote 2.5 GB into ./dem-10000, beside the checkout's files
    # (docs/study/ is the study's, whose figures and tables the docs show)
    lines = [line for _, line in DOCUMENTED + [("help", line) for _, line in EXAMPLES]]
    outside = [line for line in lines if "--out" in line.split()
               and not line.split()[line.split().index("--out") + 1].startswith(
                   ("out/", "docs/study"))]
    assert not outside, outside


# a grid a:b:n, alone or as NAME=a:b:n (not a distribution such as uniform:0.3:1)
GRID = re.compile(r"^(\w+=)?(-?[\d.]+(?:e-?\d+)?):(-?[\d.]+(?:e-?\d+)?):(\d+)$")


def shrink(sub: str, argv: list[str], scheduler) -> list[str]:
    """An example at a small size: grids a:b:n of 2 values, 3 particles of 0.5 s, 3 grains
    on a 5 cm chute, sweeps to tau = 20, the study on one roundness to tau = 20, the DEM's
    grains on a 5 cm chute with its moduli at a hundredth, the cluster address the test's
    (scheduler(), which starts the cluster the first time it is asked)."""
    out = []
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "--scheduler":
            args.pop(0)
            out += ["--scheduler", scheduler()]
        elif a in ("-n", "--particles", "--grains") and not (sub == "line" and a == "--particles"):
            args.pop(0)
            out += [a, "3"]
        elif a == "--t-end" and sub == "sweep":
            args.pop(0)
            out += ["--t-end", "20"]
        else:
            out.append(GRID.sub(r"\1\2:\3:2", a))
    if sub == "population":
        out += ["--t-end", "0.5"]
    if sub in ("line", "dem") and "--chute-length" not in out:
        out += ["--chute-length", "0.05"]
    if sub == "study":
        out += ["--epsilons", "1.0", "--t-end", "20", "--transition-width", "0.5"]
    if sub == "dem" and "--stiffness-scale" not in out:  # LIGGGHTS' time step 6.3 times
        out += ["--stiffness-scale", "0.01"]
    return out + ([] if sub == "grain" else ["--no-progress"])  # one grain shows no progress


EXAMPLES = [(sub, line) for sub in SUBCOMMANDS for line in help_examples(sub)]


def test_every_command_has_examples_in_its_help():
    assert {sub for sub, _ in EXAMPLES} == set(SUBCOMMANDS)
    assert not [line for _, line in EXAMPLES if "..." in line]  # complete, not elided


@pytest.fixture(scope="module")
def scheduler(tmp_path_factory):
    """A Dask scheduler and a worker on 127.0.0.1 (the flags of docs/sweeps.md)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    address = f"tcp://127.0.0.1:{port}"
    cwd = tmp_path_factory.mktemp("cluster")
    procs = [subprocess.Popen([PYTHON, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                               "--port", str(port), "--dashboard-address", "127.0.0.1:0",
                               "--no-dashboard"], cwd=cwd, stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)]
    procs.append(subprocess.Popen([PYTHON, "-m", "distributed.cli.dask_worker", address, "--host",
                                   "127.0.0.1", "--dashboard-address", "127.0.0.1:0",
                                   "--no-dashboard", "--nworkers", "1", "--nthreads", "2"],
                                  cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    try:
        yield address
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()


def run_example(tmp_path, request, line):
    """A command line of `tribo`, shrunk, in a fresh folder: it succeeds without a traceback.
    The test's Dask cluster is started for the first example that names one (--scheduler),
    not for every example."""
    sub, *argv = shlex.split(line, comments=True)[1:]
    # the input files an example names are the checkout's, as a user running it from the
    # checkout's root has them: they are not made up here (a made-up chutes.csv hid that
    # the documented calibration named a file nowhere to be found); a materials file under
    # out/ is another command's output, made here as that command would
    for option in ("--measured", "--impacts", "--chutes", "--materials"):
        if option in argv:
            name = argv[argv.index(option) + 1]
            path = tmp_path / name
            path.parent.mkdir(parents=True, exist_ok=True)
            if option == "--materials" and name.startswith("out/"):
                path.write_text("[sigma0.steel]\nPE = -1.5e-5\n")
            else:
                assert os.path.isfile(os.path.join(ROOT, name)), f"{line}: {name} is not in the checkout"
                shutil.copy(os.path.join(ROOT, name), path)
    argv = shrink(sub, argv, lambda: request.getfixturevalue("scheduler"))
    done = subprocess.run([command("tribo"), sub, *argv], cwd=tmp_path, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, f"tribo {sub} {' '.join(argv)}:\n{done.stderr[-3000:]}"
    assert "Traceback" not in done.stderr


@pytest.mark.parametrize("sub, line", EXAMPLES, ids=[line for _, line in EXAMPLES])
def test_each_help_example_runs(tmp_path, request, sub, line):
    run_example(tmp_path, request, line)


# the documented command lines that are not also --help examples (those run above, the
# same words but for a comment), less the mentions of a subcommand by its name alone
HELPED = {tuple(shlex.split(line, comments=True)) for _, line in EXAMPLES}
TO_RUN = sorted(line for line in {line for _, line in DOCUMENTED}
                if line.startswith("tribo ") and len(line.split()) > 2
                and tuple(shlex.split(line, comments=True)) not in HELPED)


@pytest.mark.parametrize("line", TO_RUN, ids=TO_RUN)
def test_each_documented_command_runs(tmp_path, request, line):
    run_example(tmp_path, request, line)
