"""The multi-platform FMUs of scripts/build_fmus.sh (build-fmus/, or TRIBO_FMUS_DIR), the
dimensionless and the SI pair: each holds the Linux and the Windows binary, sources/ and
documentation/ with the licences; the Windows binary, run under Wine, gives the Linux
binary's results (libm differs); sources/ lists every C file it holds (FMI 2.0:
<SourceFiles>, FMI 3.0: buildDescription.xml), and a binary compiled from them with only
sources/ and the FMI headers on the include path, by FMPy's build helper or by the plain
compiler call of fmu/README.md (each FMU one way, each way on both FMI versions), gives the
shipped one's results; the Linux binary needs
glibc 2.29 at most; the archives are reproducible."""

import glob
import html
import os
import re
import shutil
import subprocess
import xml.etree.ElementTree as ET
import zipfile

import fmpy
import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.build import build_platform_binary
from fmpy.validation import validate_fmu

from tribo_fmu import BUILD_DIR, ROOT, VERSIONS

FMUS_DIR = os.path.abspath(os.environ.get("TRIBO_FMUS_DIR", os.path.join(ROOT, "build-fmus")))
PLATFORMS = {2: ("linux64", "win64"), 3: ("x86_64-linux", "x86_64-windows")}
KIND = {"Real": "r", "Float64": "r", "Integer": "i", "Int32": "i", "Enumeration": "e",
        "Boolean": "b"}
# (stop time, step) of the runs compared: the dimensionless FMUs' defaults (the paper's
# low-friction case) to tau = 100, every unit of time; the SI FMUs' (the reference case)
# through the drop to its impact, 50 ms, every millisecond; the separator's for 1 s, every
# millisecond (its grain held at the entry: no input releases it)
RUNS = {"tribo": (100, 1), "tribo_si": (0.05, 1e-3), "tribo_separator": (0.2, 1e-3)}
# what a run needs set to move: the separator's grain is held at the entry until released
# (its input, value reference 101); 0.2 s is before it lands (0.36 s at the defaults)
START = {"tribo_separator": {"released": True}}
CHECK_SETTINGS = {"tribo_separator": ["b101=1"]}
# the run moved: the dimensionless particle past X = 1 down the plate, the SI drop and the
# separator's fall each more than 5 mm down
MOVED = {"tribo": ("X", lambda first, last: last > 1),
         "tribo_si": ("y", lambda first, last: first - last > 5e-3),
         "tribo_separator": ("z", lambda first, last: first - last > 5e-3)}
PREFIXES = tuple(RUNS)
DESCRIPTION = {"tribo": "fmi{v}.xml", "tribo_si": "tribo_si_fmi{v}.xml",
               "tribo_separator": "tribo_separator_fmi{v}.xml"}
every_fmu = pytest.mark.parametrize("prefix", PREFIXES)


def release(version, prefix="tribo"):
    path = os.path.join(FMUS_DIR, f"{prefix}_fmi{version}.fmu")
    if not os.path.exists(path):
        pytest.fail(f"{path} is missing: run scripts/build_fmus.sh (scripts/test.sh does)")
    return path


@pytest.fixture(scope="module")
def unpacked(tmp_path_factory):
    dirs = {}

    def unpack(version, prefix="tribo"):
        if (prefix, version) not in dirs:
            dirs[prefix, version] = str(tmp_path_factory.mktemp(f"release_{prefix}{version}"))
            with zipfile.ZipFile(release(version, prefix)) as z:
                z.extractall(dirs[prefix, version])
        return dirs[prefix, version]

    return unpack


def source_files(unzipped):
    """The C files to compile, as the FMU lists them: FMI 2.0 in the modelDescription's
    <SourceFiles>, FMI 3.0 in sources/buildDescription.xml."""
    root = ET.parse(os.path.join(unzipped, "modelDescription.xml")).getroot()
    if root.get("fmiVersion") == "2.0":
        return [f.get("name") for f in root.findall("CoSimulation/SourceFiles/File")]
    build = ET.parse(os.path.join(unzipped, "sources", "buildDescription.xml")).getroot()
    return [f.get("name") for f in build.iter("SourceFile")]


def scalar_outputs(unzipped):
    md = read_model_description(unzipped, validate=False)
    return [f"{KIND[v.type]}{v.valueReference}" for v in md.modelVariables
            if v.causality == "output" and not v.dimensions], md.guid


def check_run(command, binary, version, token, outputs, prefix):
    stop, step = RUNS[prefix]
    settings = ["--"] + CHECK_SETTINGS[prefix] if prefix in CHECK_SETTINGS else []
    out = subprocess.run(command + [binary, str(version), token, str(stop), str(step)] + outputs
                         + settings,
                         capture_output=True, text=True, env=dict(os.environ, WINEDEBUG="-all"),
                         timeout=300)
    assert out.returncode == 0, out.stderr
    return np.array([[float(x) for x in line.split()] for line in out.stdout.splitlines()])


NATIVE_CHECK = [os.path.join(BUILD_DIR, "fmu", "tribo_platform_check")]


@every_fmu
@pytest.mark.parametrize("version", VERSIONS)
def test_release_layout(unpacked, version, prefix):
    """The FMU's files; in sources/, the C files whose objects the binaries link
    (fmu/tools/make_sources.py): the FMU's own core and CVODE, not another FMU's core or
    the parts of SUNDIALS that CVODE does not call."""
    with zipfile.ZipFile(release(version, prefix)) as z:
        names = set(z.namelist())
    linux, windows = PLATFORMS[version]
    front_ends = {"tribo": ("front_end_model.c", "variables_model.c"),
                  "tribo_si": ("front_end_si.c", "variables_si.c"),
                  "tribo_separator": ("front_end_separator.c", "variables_separator.c")}
    assert {f"sources/tribo/{f}" for f in front_ends[prefix]} <= names
    assert all(f"sources/tribo/{f}" not in names for p, fs in front_ends.items() if p != prefix
               for f in fs)
    unpacked_dir = unpacked(version, prefix)
    id = f"{prefix}_fmi{version}"
    own, other = ("separator.c", "model.c") if prefix == "tribo_separator" else ("model.c", "separator.c")
    assert {f"binaries/{linux}/{id}.so", f"binaries/{windows}/{id}.dll",
            "modelDescription.xml", "documentation/index.html",
            "documentation/licenses/license.txt", "documentation/licenses/SUNDIALS-LICENSE",
            "sources/buildDescription.xml", "sources/sundials/LICENSE", "sources/tribo/LICENSE",
            f"sources/tribo/fmi{version}.c", f"sources/tribo/{own}", "sources/tribo/quantities.def",
            "sources/tribo/instantiation_token.h", "sources/sundials/cvode.c",
            "sources/sundials/sundials_config.h", "sources/cvode/cvode.h"} <= names
    assert not {f"sources/tribo/fmi{5 - version}.c", f"sources/tribo/{other}",
                "sources/sundials/sunlinsol_spgmr.c", "sources/sundials/sunmatrix_sparse.c",
                "sources/sundials/cvode_bandpre.c"} & names
    # only what compiles in C: no C++ interfaces of SUNDIALS, none of its unused solvers
    assert not [n for n in names if n.endswith(".hpp") or n.startswith(("sources/arkode/", "sources/ida/"))]
    with open(os.path.join(ROOT, "LICENSE"), "rb") as f:
        assert open(os.path.join(unpacked_dir, "documentation/licenses/license.txt"), "rb").read() == f.read()
    with open(os.path.join(BUILD_DIR, "fmu", DESCRIPTION[prefix].format(v=version)), encoding="utf-8") as f:
        generated = f.read()
    packed = open(os.path.join(unpacked_dir, "modelDescription.xml"), encoding="utf-8").read()
    if version == 2:
        # the generated description, with <SourceFiles> in its CoSimulation element
        assert packed.count("<SourceFiles>") == 1
        packed = re.sub(r">\s*<SourceFiles>.*</SourceFiles>\s*</CoSimulation>", "/>", packed, flags=re.S)
    assert packed == generated
    assert "BSD 3-Clause" in open(os.path.join(unpacked_dir, "sources/sundials/LICENSE")).read()
    assert validate_fmu(release(version, prefix)) == []


@every_fmu
@pytest.mark.parametrize("version", VERSIONS)
def test_sources_list_every_c_file_they_hold(unpacked, version, prefix):
    """Both FMI versions list the same files in their own way, and every C file in
    sources/ among them: `sources/*/*.c` is the build (fmu/README.md)."""
    u = unpacked(version, prefix)
    listed = source_files(u)

    def held(pattern):
        return sorted(os.path.relpath(f, os.path.join(u, "sources")).replace(os.sep, "/")
                      for f in glob.glob(os.path.join(u, "sources", pattern), recursive=True))

    assert len(listed) > 20 and sorted(listed) == held("**/*.c") == held("*/*.c")
    build = ET.parse(os.path.join(u, "sources", "buildDescription.xml")).getroot()
    assert [f.get("name") for f in build.iter("SourceFile")] == listed
    assert build.find("BuildConfiguration").get("modelIdentifier") == f"{prefix}_fmi{version}"
    # no include directory but sources/ itself, no definition an importer must make
    assert build.find(".//IncludeDirectory") is None
    assert all(d.get("optional") == "true" for d in build.iter("PreprocessorDefinition"))


@every_fmu
@pytest.mark.parametrize("version", VERSIONS)
def test_documentation_lists_every_variable(unpacked, version, prefix):
    page = open(os.path.join(unpacked(version, prefix), "documentation", "index.html"), encoding="utf-8").read()
    md = read_model_description(unpacked(version, prefix), validate=False)
    for v in md.modelVariables:
        row = re.search(rf"<tr><td>{re.escape(v.name)}</td><td>{v.valueReference}</td>.*?</tr>", page)
        assert row, v.name
        assert html.escape(v.description) in row.group(0), v.name
        if v.unit:
            assert f"<td>{v.unit}" in row.group(0), v.name
    # every enumeration the FMU declares is documented
    types = [t.name for t in md.typeDefinitions if t.type == "Enumeration"]
    assert types and all(t in page for t in types), types
    assert "licenses/license.txt" in page
    assert "<h2>The model</h2>" in page


@every_fmu
@pytest.mark.parametrize("version", VERSIONS)
def test_windows_binary_under_wine_matches_linux(unpacked, version, prefix):
    """Measured: at most 9.9e-11 relative (pointwise) to tau = 100 in the paper's
    low-friction case; the bound is 1e-9. Flags, classes and counts are equal."""
    outputs, token = scalar_outputs(unpacked(version, prefix))
    linux, windows = PLATFORMS[version]
    base = os.path.join(unpacked(version, prefix), "binaries")
    id = f"{prefix}_fmi{version}"
    native = check_run(NATIVE_CHECK, os.path.join(base, linux, f"{id}.so"), version, token,
                       outputs, prefix)
    exe = os.path.join(FMUS_DIR, "win64", "fmu", "tribo_platform_check.exe")
    wine = check_run(["wine", exe], os.path.join(base, windows, f"{id}.dll"), version, token,
                     outputs, prefix)
    stop, step = RUNS[prefix]
    assert native.shape == wine.shape == (round(stop / step) + 1, len(outputs) + 1)
    exact = [0] + [i + 1 for i, o in enumerate(outputs) if o[0] != "r"]
    assert np.array_equal(native[:, exact], wine[:, exact])
    scale = np.maximum(np.abs(native), np.abs(wine))
    relative = np.abs(native - wine) / np.where(scale > 0, scale, 1)
    assert relative.max() <= 1e-9, (relative.max(), outputs[int(np.argmax(relative.max(axis=0))) - 1])
    # the particle moved: the comparison saw a run
    name, moved = MOVED[prefix]
    md = read_model_description(unpacked(version, prefix), validate=False)
    code = next(f"r{v.valueReference}" for v in md.modelVariables if v.name == name)
    column = 1 + outputs.index(code)
    assert moved(native[0, column], native[-1, column])


FMI_HEADERS = os.path.join(os.path.dirname(fmpy.__file__), "c-code")


def readme_compiler_call():
    """The plain compiler call fmu/README.md documents for a platform without a binary."""
    with open(os.path.join(ROOT, "fmu", "README.md"), encoding="utf-8") as f:
        calls = [line for line in f.read().splitlines() if line.startswith("cc ")]
    assert len(calls) == 1, calls
    return calls[0]


def compile_with_fmpy(tmp_path_factory, version, prefix):
    """The FMU unzipped afresh, its Linux binary removed and compiled again from its
    sources/ by FMPy's build helper (what `fmpy compile` runs): the unzipped FMU."""
    unzipped = tmp_path_factory.mktemp(f"fmpy_built_{prefix}{version}")
    with zipfile.ZipFile(release(version, prefix)) as z:
        z.extractall(unzipped)
    shutil.rmtree(unzipped / "binaries" / PLATFORMS[version][0])
    build_platform_binary(unzipped, build_dir=tmp_path_factory.mktemp(f"fmpy_build_{prefix}{version}"))
    return str(unzipped)


def compile_with_cc(tmp_path_factory, version, prefix):
    """The FMU's sources/ compiled by fmu/README.md's call, as it is written there: the
    binary."""
    unzipped = tmp_path_factory.mktemp(f"cc_built_{prefix}{version}")
    with zipfile.ZipFile(release(version, prefix)) as z:
        z.extractall(unzipped, [n for n in z.namelist() if n.startswith("sources/")])
    binary = str(unzipped / f"{prefix}_fmi{version}.so")
    out = subprocess.run(["bash", "-c", readme_compiler_call()], cwd=unzipped,
                         env=dict(os.environ, FMI_HEADERS=FMI_HEADERS, BINARY=binary),
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr[-3000:]
    return binary


# Each source FMU compiled once, by one of the two ways, the ways alternating so that each
# takes both FMI versions (the README's call both FMI layers, FMPy's helper both listings:
# <SourceFiles> and buildDescription.xml, which test_sources_list_every_c_file_they_hold
# checks against sources/ for every FMU)
BY_COMPILER_CALL = [("tribo", 2), ("tribo_si", 3), ("tribo_separator", 2)]
BY_FMPY = [("tribo", 3), ("tribo_si", 2), ("tribo_separator", 3)]


@pytest.mark.parametrize("prefix, version", BY_COMPILER_CALL)
def test_plain_compiler_call_on_the_sources_gives_the_shipped_results(tmp_path_factory, unpacked, version, prefix):
    """fmu/README.md's call: only sources/ and the FMI headers on the include path, no
    definition. Bit-identical results (measured)."""
    rebuilt = compile_with_cc(tmp_path_factory, version, prefix)
    outputs, token = scalar_outputs(unpacked(version, prefix))
    shipped = os.path.join(unpacked(version, prefix), "binaries", PLATFORMS[version][0],
                           f"{prefix}_fmi{version}.so")
    assert np.array_equal(check_run(NATIVE_CHECK, rebuilt, version, token, outputs, prefix),
                          check_run(NATIVE_CHECK, shipped, version, token, outputs, prefix))


def test_each_source_fmu_is_compiled_one_way_and_each_way_takes_both_versions():
    assert sorted(BY_COMPILER_CALL + BY_FMPY) == sorted((p, v) for p in PREFIXES for v in VERSIONS)
    for ways in (BY_COMPILER_CALL, BY_FMPY):
        assert {v for _, v in ways} == set(VERSIONS)


@pytest.mark.parametrize("prefix, version", BY_FMPY)
def test_fmpy_build_helper_compiles_the_sources_to_the_shipped_results(tmp_path_factory, version, prefix):
    """FMPy puts only sources/ on the include path, reads FMI 2.0's <SourceFiles> and FMI
    3.0's buildDescription.xml; its binary, simulated by fmpy, gives the shipped binary's
    results bit for bit, every scalar output at every communication point (measured)."""
    rebuilt = compile_with_fmpy(tmp_path_factory, version, prefix)
    binary = os.path.join(rebuilt, "binaries", PLATFORMS[version][0], f"{prefix}_fmi{version}.so")
    assert os.path.exists(binary)
    md = read_model_description(rebuilt)
    outputs = [v.name for v in md.modelVariables if v.causality == "output" and not v.dimensions]
    stop, step = RUNS[prefix]
    runs = [simulate_fmu(fmu, stop_time=stop, output_interval=step, output=outputs,
                         start_values=START.get(prefix, {}))
            for fmu in (rebuilt, release(version, prefix))]
    assert runs[0].dtype.names == runs[1].dtype.names and len(runs[0]) == round(stop / step) + 1
    assert all(np.array_equal(runs[0][n], runs[1][n]) for n in runs[0].dtype.names)
    # the particle moved: the comparison saw a run
    name, moved = MOVED[prefix]
    assert moved(runs[0][name][0], runs[0][name][-1])


@every_fmu
@pytest.mark.parametrize("version", VERSIONS)
def test_windows_binary_needs_only_system_dlls(unpacked, version, prefix):
    dll = os.path.join(unpacked(version, prefix), "binaries", PLATFORMS[version][1],
                       f"{prefix}_fmi{version}.dll")
    dump = subprocess.run(["x86_64-w64-mingw32-objdump", "-p", dll], capture_output=True, text=True,
                          check=True).stdout
    assert set(re.findall(r"DLL Name: (\S+)", dump)) == {"KERNEL32.dll", "msvcrt.dll"}
    exports = set(re.findall(rf"\]\s+(fmi{version}\w+)$", dump, re.M))
    assert len(exports) > 40 and all(e.startswith(f"fmi{version}") for e in exports)


@every_fmu
@pytest.mark.parametrize("version", VERSIONS)
def test_linux_binary_needs_glibc_2_29_at_most(version, prefix):
    """exp and pow at GLIBC_2.29 (glibc's faster versions); everything else 2.14 at most."""
    so = os.path.join(BUILD_DIR, "fmu", "lib", f"{prefix}_fmi{version}.so")
    dump = subprocess.run(["objdump", "-T", so], capture_output=True, text=True, check=True).stdout
    versions = {tuple(map(int, v.split("."))) for v in re.findall(r"GLIBC_([\d.]+)", dump)}
    assert max(versions) == (2, 29)
    newest = set(re.findall(r"GLIBC_2\.29\)?\s+(\w+)", dump))
    assert newest <= {"exp", "pow", "log"}, newest


@every_fmu
@pytest.mark.parametrize("version", VERSIONS)
def test_archive_is_reproducible(unpacked, tmp_path, version, prefix):
    """Packing the same inputs again gives the same bytes (sorted entries, fixed dates)."""
    u = unpacked(version, prefix)
    id = f"{prefix}_fmi{version}"
    linux, windows = PLATFORMS[version]
    again = str(tmp_path / "again.fmu")
    with zipfile.ZipFile(release(version, prefix)) as z:
        date = z.infolist()[0].date_time
    import calendar
    epoch = calendar.timegm(date + (0, 0, 0))
    subprocess.run([os.path.join(ROOT, ".venv", "bin", "python"),
                    os.path.join(ROOT, "fmu", "tools", "pack_fmu.py"), "--out", again,
                    "--description", os.path.join(u, "modelDescription.xml"),
                    "--model-doc", os.path.join(ROOT, "docs", "model.md"),
                    "--binary", f"{linux}={u}/binaries/{linux}/{id}.so",
                    "--binary", f"{windows}={u}/binaries/{windows}/{id}.dll",
                    "--license", f"license.txt={u}/documentation/licenses/license.txt",
                    "--license", f"SUNDIALS-LICENSE={u}/documentation/licenses/SUNDIALS-LICENSE",
                    "--sources", os.path.join(u, "sources"), "--epoch", str(epoch)], check=True)
    assert open(again, "rb").read() == open(release(version, prefix), "rb").read()
