"""tests/check_sources.py, the check of src/'s layout that ctest runs (test_source_layout):
it passes on src/ and fails, naming the files, on small made-up trees with each defect it
looks for."""

import os
import shutil
import subprocess
import sys

import pytest

from tribo_fmu import ROOT

CHECK = os.path.join(ROOT, "tests", "check_sources.py")


def check(*args):
    return subprocess.run([sys.executable, CHECK, *map(str, args)], capture_output=True,
                          text=True)


def tree(root, files):
    """A made-up src/: {path: text}."""
    for path, text in files.items():
        os.makedirs(os.path.dirname(root / path), exist_ok=True)
        (root / path).write_text(text)
    return root


def test_src_passes():
    out = check(os.path.join(ROOT, "src"))
    assert out.returncode == 0, out.stdout


def test_a_name_in_two_folders_is_refused(tmp_path):
    src = tree(tmp_path, {"common/a.h": "", "chute/a.h": ""})
    out = check(src)
    assert out.returncode == 1 and "a.h is in both chute/ and common/" in out.stdout


def test_an_include_cycle_is_refused(tmp_path):
    src = tree(tmp_path, {"chute/a.h": '#include "b.h"\n', "chute/b.h": '#include "a.h"\n'})
    out = check(src)
    assert out.returncode == 1 and "an include cycle: a.h -> b.h; b.h -> a.h" in out.stdout


def test_a_c_file_including_the_header_of_one_that_includes_its_own_is_refused(tmp_path):
    # model.c <-> registry.c through each other's headers: the cycle of the charge outputs
    src = tree(tmp_path, {"chute/model.h": '#include "registry.h"\n',
                          "chute/model.c": '#include "model.h"\n',
                          "chute/registry.h": "",
                          "chute/registry.c": '#include "registry.h"\n#include "model.h"\n'})
    out = check(src)
    assert out.returncode == 1
    assert "model -> registry (model.h includes registry.h)" in out.stdout
    assert "registry -> model (registry.c includes model.h)" in out.stdout


def test_an_include_a_folder_may_not_make_is_refused(tmp_path):
    src = tree(tmp_path, {"chute/model.h": "", "separator/separator.c": '#include "model.h"\n'})
    out = check(src)
    assert out.returncode == 1
    assert "separator/separator.c includes chute/model.h" in out.stdout


def test_an_include_of_no_file_of_src_is_refused(tmp_path):
    src = tree(tmp_path, {"chute/a.c": '#include "missing.h"\n'})
    out = check(src)
    assert out.returncode == 1 and "no file of src/" in out.stdout


@pytest.mark.skipif(not shutil.which("cc") or not shutil.which("ar"), reason="needs cc and ar")
def test_objects_that_use_each_other_are_refused(tmp_path):
    # no include between them, and each calls the other: only the symbols show the cycle
    src = tree(tmp_path / "src", {"chute/a.c": "int b(void);\nint a(void) { return b(); }\n",
                                  "chute/b.c": "int a(void);\nint b(void) { return a(); }\n"})
    objects = []
    for name in ("a", "b"):
        obj = tmp_path / f"{name}.c.o"
        subprocess.run(["cc", "-c", src / "chute" / f"{name}.c", "-o", obj], check=True)
        objects.append(obj)
    library = tmp_path / "libcore.a"
    subprocess.run(["ar", "rcs", library, *objects], check=True)
    out = check(src, library)
    assert out.returncode == 1
    assert "a.c -> b.c (b); b.c -> a.c (a)" in out.stdout
