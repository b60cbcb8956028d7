"""Every example runs as written: each ```python block of README.md and of the user guide's
pages (docs/README.md's table), saved as a script and run in a fresh folder with the venv's
Python, and each example line of the four commands' --help.

The blocks run as they are: they are small on purpose. The --help examples show sizes a
user would run (1000 particles, tau to 1000, an existing cluster); they run here at a small
size, by the substitutions in `shrink` (each one named there), and the cluster examples on
a scheduler and a worker started for the test."""

import os
import re
import shlex
import socket
import subprocess
import sys

import pytest

from study_support import PYTHON, command
from tribo_fmu import ROOT

COMMANDS = ["tribo-study", "tribo-sweep", "tribo-population", "tribo-impact-map"]


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


def help_examples(name: str) -> list[str]:
    """The example command lines of a command's --help (indented, starting with its name;
    a trailing backslash continues a line)."""
    text = subprocess.run([command(name), "--help"], capture_output=True, text=True, check=True,
                          timeout=60).stdout
    examples, current = [], None
    for line in text.splitlines():
        stripped = line.strip()
        if current is not None:
            current += " " + stripped.rstrip("\\").strip()
            if not stripped.endswith("\\"):
                examples.append(current)
                current = None
        elif line.startswith("    ") and stripped.startswith(name + " "):
            if stripped.endswith("\\"):
                current = stripped.rstrip("\\").strip()
            else:
                examples.append(stripped)
    return examples


# a grid a:b:n, alone or as NAME=a:b:n (not a distribution such as uniform:0.3:1)
GRID = re.compile(r"^(\w+=)?(-?[\d.]+(?:e-?\d+)?):(-?[\d.]+(?:e-?\d+)?):(\d+)$")


def shrink(name: str, argv: list[str], scheduler: str) -> list[str]:
    """An example at a small size: grids a:b:n of 2 values, 3 particles of 0.5 s, sweeps to
    tau = 20, the study on one roundness to tau = 20, the cluster address the test's."""
    out = []
    args = list(argv)
    while args:
        a = args.pop(0)
        if a == "--scheduler":
            args.pop(0)
            out += ["--scheduler", scheduler]
        elif a in ("-n", "--particles"):
            args.pop(0)
            out += [a, "3"]
        elif a == "--t-end" and name == "tribo-sweep":
            args.pop(0)
            out += ["--t-end", "20"]
        else:
            out.append(GRID.sub(r"\1\2:\3:2", a))
    if name == "tribo-population":
        out += ["--t-end", "0.5"]
    if name == "tribo-study":
        out += ["--epsilons", "1.0", "--t-end", "20", "--transition-width", "0.5"]
    return out + ["--no-progress"]


EXAMPLES = [(name, line) for name in COMMANDS for line in help_examples(name)]


def test_every_command_has_examples_in_its_help():
    assert {name for name, _ in EXAMPLES} == set(COMMANDS)
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


@pytest.mark.parametrize("name, line", EXAMPLES, ids=[line for _, line in EXAMPLES])
def test_each_help_example_runs(tmp_path, scheduler, name, line):
    argv = shlex.split(line, comments=True)[1:]
    if "--measured" in argv:  # the example's sieve data: a column per feed variable measured
        (tmp_path / argv[argv.index("--measured") + 1]).write_text(
            "epsilon,size\n0.45,4e-4\n0.7,8e-4\n0.9,1.2e-3\n")
    argv = shrink(name, argv, scheduler)
    done = subprocess.run([command(name), *argv], cwd=tmp_path, capture_output=True, text=True,
                          timeout=300)
    assert done.returncode == 0, f"{name} {' '.join(argv)}:\n{done.stderr[-3000:]}"
    assert "Traceback" not in done.stderr
