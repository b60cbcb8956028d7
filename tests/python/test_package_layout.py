"""The package's layout (python/tribo, CONTRIBUTING.md): every module imports in a fresh
interpreter, no module imports itself back through others, each concern imports only
those below it, a function-local import says why, and `import tribo` leaves the heavy
optional dependencies unloaded."""

import ast
import json
import os
import pkgutil
import subprocess
import sys

import tribo
from tribo.cli.main import SUBCOMMANDS

PACKAGE_DIR = os.path.dirname(tribo.__file__)
# the concerns from the bottom up: a module may import its own concern's modules and those
# of a lower layer (tribo/__init__.py says the same)
LAYERS = {"tribo.plotting": 0, "tribo.fmu": 0, "tribo.materials": 1, "tribo.paschen": 1,
          "tribo.batch": 1,
          "tribo.study": 2, "tribo.populations": 2, "tribo.impact": 2, "tribo.line": 3, "tribo.calibration": 3,
          "tribo.dem": 3,
          "tribo.api": 4, "tribo.cli": 5, "tribo": 6}
# what `import tribo` must not load: the package imports them where they are used (plots,
# Dask runs, map lookups), each such import with its reason
HEAVY = ("matplotlib", "distributed", "dask", "scipy")


def modules() -> list[str]:
    names = ["tribo"] + [m.name for m in pkgutil.walk_packages(tribo.__path__, "tribo.")]
    return sorted(names)


def source_of(module: str) -> str:
    parts = module.split(".")[1:]
    path = os.path.join(PACKAGE_DIR, *parts)
    return os.path.join(path, "__init__.py") if os.path.isdir(path) else path + ".py"


def is_package(module: str) -> bool:
    return source_of(module).endswith("__init__.py")


def imports_of(module: str) -> list[tuple[str, ast.AST]]:
    """The package's modules that `module` imports, anywhere in it (function bodies too),
    with the import statement: `from X import name` counts as X.name where that is a
    module, else as X."""
    known = set(modules())
    tree = ast.parse(open(source_of(module), encoding="utf-8").read())
    here = module if is_package(module) else module.rpartition(".")[0]
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(a.name, node) for a in node.names if a.name in known]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = here.split(".")
                base = base[:len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "tribo":
                continue
            for a in node.names:
                sub = f"{target}.{a.name}"
                out.append((sub if sub in known else target, node))
    return out


def concern(module: str) -> str:
    for c in sorted(LAYERS, key=len, reverse=True):
        if module == c or module.startswith(c + "."):
            return c
    raise AssertionError(f"{module} belongs to no concern of LAYERS: place it in one")


def test_every_module_imports_in_a_fresh_interpreter():
    """Each module with the package's modules unloaded before it: none imports only thanks
    to one imported earlier."""
    script = ("import importlib, sys\n"
              "for name in sys.argv[1:]:\n"
              "    for loaded in [m for m in sys.modules if m.split('.')[0] == 'tribo']:\n"
              "        del sys.modules[loaded]\n"
              "    importlib.import_module(name)\n"
              "print('imported', len(sys.argv) - 1)\n")
    done = subprocess.run([sys.executable, "-c", script, *modules()], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == f"imported {len(modules())}"


def import_graph() -> dict:
    """module -> the package's modules it imports."""
    return {m: {target for target, _ in imports_of(m)} - {m} for m in modules()}


def find_cycles(graph: dict) -> list[list[str]]:
    """Every cycle a depth-first walk meets, as [a, b, ..., a]."""
    visiting, done, cycles = [], set(), []

    def visit(m):
        if m in visiting:
            cycles.append(visiting[visiting.index(m):] + [m])
            return
        if m in done:
            return
        visiting.append(m)
        for n in sorted(graph[m]):
            visit(n)
        visiting.pop()
        done.add(m)

    for m in sorted(graph):
        visit(m)
    return cycles


def test_no_module_imports_itself_back():
    cycles = find_cycles(import_graph())
    assert not cycles, [" -> ".join(c) for c in cycles]


def test_the_cycle_check_sees_a_cycle_through_a_function_local_import(tmp_path, monkeypatch):
    """(So that the test above would fail on two modules importing each other, one of them
    inside a function to dodge the cycle at import time.)"""
    fake = {"tribo.a": "from .b import x\n", "tribo.b": "def f():\n    from . import a\n",
            "tribo.c": "from tribo.a import x\n"}
    for name, text in fake.items():
        (tmp_path / f"{name}.py").write_text(text)
    this = sys.modules[__name__]
    monkeypatch.setattr(this, "modules", lambda: sorted(fake))
    monkeypatch.setattr(this, "source_of", lambda m: str(tmp_path / f"{m}.py"))
    assert find_cycles(import_graph()) == [["tribo.a", "tribo.b", "tribo.a"]]


def test_each_concern_imports_only_its_own_modules_and_lower_layers():
    wrong = []
    for m in modules():
        for target, node in imports_of(m):
            a, b = concern(m), concern(target)
            if a != b and LAYERS[b] >= LAYERS[a]:
                wrong.append(f"{m} (line {node.lineno}) imports {target}")
    assert not wrong, wrong


def test_a_function_local_import_says_why():
    """An import inside a function is there for a reason (an optional heavy dependency
    loaded where it is used), written beside it or on the line above."""
    silent = []
    for m in modules():
        lines = open(source_of(m), encoding="utf-8").read().splitlines()
        tree = ast.parse("\n".join(lines))
        for function in (n for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))):
            for node in ast.walk(function):
                if isinstance(node, (ast.Import, ast.ImportFrom)):
                    around = lines[node.lineno - 1] + lines[node.lineno - 2]
                    if "#" not in around:
                        silent.append(f"{m}:{node.lineno}: {lines[node.lineno - 1].strip()}")
    assert not silent, silent


def modules_loaded_by(code: str) -> set:
    """The modules a fresh interpreter has imported after running code."""
    script = f"import json, sys\n{code}\nprint(json.dumps(sorted(sys.modules)))"
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          timeout=60)
    assert done.returncode == 0, done.stderr
    return set(json.loads(done.stdout.strip().splitlines()[-1]))


def modules_loaded_by_the_command(argv: list) -> set:
    """The modules a fresh interpreter has imported after `tribo argv` (main(argv))."""
    return modules_loaded_by(f"from tribo.cli.main import main\ntry:\n    main({argv!r})\n"
                             f"except SystemExit:\n    pass")


def test_importing_tribo_leaves_the_heavy_optional_dependencies_unloaded():
    assert not {m.split(".")[0] for m in modules_loaded_by("import tribo")} & set(HEAVY)


JOB_LIBRARIES = {"numpy", "pandas", "fmpy", "matplotlib", "dask", "distributed", "scipy"}


def test_the_commands_help_imports_no_job_library():
    """`tribo --help`, a mistake in the subcommand's name and each subcommand's --help are
    answered by the parser alone: the options are made of constants, and a job's modules
    (with numpy, pandas, fmpy, Dask, matplotlib, scipy) are imported once it runs; a
    subcommand's parser imports its own module, not the other subcommands'."""
    for argv in (["--help"], ["bogus"], []):
        loaded = {m.split(".")[0] for m in modules_loaded_by_the_command(argv)}
        assert not loaded & JOB_LIBRARIES, (argv, loaded & JOB_LIBRARIES)
    for name, (module, _) in SUBCOMMANDS.items():
        loaded = modules_loaded_by_the_command([name, "--help"])
        assert f"tribo.cli.{module}" in loaded, name
        heavy = {m.split(".")[0] for m in loaded} & JOB_LIBRARIES
        assert not heavy, (name, heavy)
        others = {m for m in loaded if m.startswith("tribo.cli.") and m.split(".")[2] in
                  {other for other, _ in SUBCOMMANDS.values()} - {module}}
        assert not others, (name, others)
