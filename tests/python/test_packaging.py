"""The .fmu archives: their layout, a binary that needs nothing but the C library and
exports nothing but the FMI functions, and a build that repacks them when a source
changes."""

import os
import re
import shutil
import subprocess
import zipfile

import fmpy
import pytest

from tribo_fmu import BUILD_DIR, ROOT, VERSIONS

PLATFORM = {2: fmpy.platform, 3: fmpy.platform_tuple}
# what any Linux program gets: the C library, libm, the loader and the kernel's vDSO
SYSTEM_LIBRARIES = re.compile(r"^(linux-vdso\.so\.1|libc\.so\.6|libm\.so\.6|/lib64/ld-linux-x86-64\.so\.2"
                              r"|/lib/ld-linux[-\w.]*\.so\.\d)$")


def binary(fmu_dir, version):
    return os.path.join(fmu_dir(version), "binaries", PLATFORM[version], f"tribo_fmi{version}.so")


def fmi_functions_declared(version):
    """Every function fmpy's copy of fmi<v>Functions.h declares."""
    header = os.path.join(os.path.dirname(fmpy.__file__), "c-code", f"fmi{version}Functions.h")
    with open(header) as f:
        return set(re.findall(rf"FMI{version}_Export\s+fmi{version}\w+TYPE\s+(fmi{version}\w+);",
                              f.read()))


@pytest.mark.parametrize("version", VERSIONS)
def test_archive_layout(fmu_file, version):
    with zipfile.ZipFile(fmu_file(version)) as z:
        files = {n for n in z.namelist() if not n.endswith("/")}
    assert files == {"modelDescription.xml", f"binaries/{PLATFORM[version]}/tribo_fmi{version}.so",
                     "documentation/index.html", "documentation/licenses/license.txt",
                     "documentation/licenses/SUNDIALS-LICENSE"} | \
        ({"documentation/_main.html"} if version == 2 else set())


@pytest.mark.parametrize("version", VERSIONS)
def test_binary_needs_only_the_c_library(fmu_dir, version):
    out = subprocess.run(["ldd", binary(fmu_dir, version)], capture_output=True, text=True,
                         check=True).stdout
    needed = [line.split()[0] for line in out.splitlines() if line.strip()]
    assert needed and all(SYSTEM_LIBRARIES.match(n) for n in needed), needed
    assert not any("sundials" in line for line in out.splitlines())


@pytest.mark.parametrize("version", VERSIONS)
def test_binary_exports_exactly_the_fmi_functions(fmu_dir, version):
    out = subprocess.run(["nm", "-D", "--defined-only", binary(fmu_dir, version)],
                         capture_output=True, text=True, check=True).stdout
    symbols = {line.split()[-1]: line.split()[-2] for line in out.splitlines()}
    declared = fmi_functions_declared(version)
    assert len(declared) > 40
    assert set(symbols) == declared
    assert set(symbols.values()) == {"T"}


# each pair of FMUs links one front end (fmu/front_end.h) and its variable table
FRONT_ENDS = {"tribo": ("fmu/front_end_model.c", "fmu/variables_model.c", "fmu/front_end_chute.c",
                        "fmu/front_end_identity.c"),
              "tribo_si": ("fmu/front_end_si.c", "fmu/variables_si.c", "fmu/front_end_chute.c"),
              "tribo_separator": ("fmu/front_end_separator.c", "fmu/variables_separator.c",
                                  "fmu/front_end_identity.c")}


@pytest.mark.parametrize("prefix", FRONT_ENDS)
@pytest.mark.parametrize("version", VERSIONS)
def test_fmu_is_rebuilt_from_its_sources(version, prefix):
    """Every source the FMU is made of, its generated modelDescription's included, is an
    input of the .fmu in the build graph, so editing any of them repacks it."""
    if not os.path.exists(os.path.join(BUILD_DIR, "build.ninja")) or not shutil.which("ninja"):
        pytest.fail(f"{BUILD_DIR} is not a Ninja build directory (scripts/setup.sh makes one)")

    def sources(target):
        out = subprocess.run(["ninja", "-C", BUILD_DIR, "-t", "inputs", target],
                             capture_output=True, text=True, check=True).stdout
        return {os.path.relpath(p, ROOT) for p in out.split() if p.startswith(ROOT + os.sep)}

    inputs = sources(f"fmu/{prefix}_fmi{version}.fmu")
    fmu_sources = {os.path.join("fmu", f) for f in os.listdir(os.path.join(ROOT, "fmu"))
                   if f.endswith(".c") and f not in ("fmi2.c", "fmi3.c")}
    fmu_sources -= {f for fs in FRONT_ENDS.values() for f in fs} - set(FRONT_ENDS[prefix])
    core_sources = sources("libtribo_core.a")
    assert "src/chute/model.c" in core_sources
    expected = fmu_sources | core_sources | {f"fmu/fmi{version}.c", f"fmu/fmi{version}.map",
                                             "fmu/tools/model_description.c", "fmu/token.cmake",
                                             "fmu/tools/pack_fmu.py", "docs/model.md", "LICENSE"}
    assert expected <= inputs, expected - inputs
