"""The tools that make a source FMU's sources/ (fmu/tools/make_sources.py) and its FMI 2.0
<SourceFiles> (fmu/tools/add_source_files.py): what they write, and the one-line refusals
of input they cannot use, on small made-up trees (no SUNDIALS needed)."""

import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import pytest

from tribo_fmu import BUILD_DIR, ROOT

TOOLS = os.path.join(ROOT, "fmu", "tools")


def tool(name, *args, cwd=None):
    return subprocess.run([sys.executable, os.path.join(TOOLS, name), *map(str, args)],
                          capture_output=True, text=True, cwd=cwd)


def refused(out, *words):
    """A refusal: a failing exit and one line on stderr saying why."""
    assert out.returncode != 0 and out.stdout == ""
    assert len(out.stderr.strip().splitlines()) == 1, out.stderr
    assert all(w in out.stderr for w in words), out.stderr


def test_source_files_go_into_the_fmi2_description_and_nothing_else_changes(tmp_path):
    description = os.path.join(BUILD_DIR, "fmu", "fmi2.xml")
    build = tmp_path / "buildDescription.xml"
    build.write_text('<fmiBuildDescription fmiVersion="3.0"><BuildConfiguration modelIdentifier="x">'
                     '<SourceFileSet><SourceFile name="tribo/a.c"/><SourceFile name="sundials/b &amp; c.c"/>'
                     '</SourceFileSet></BuildConfiguration></fmiBuildDescription>')
    out = tool("add_source_files.py", description, build)
    assert out.returncode == 0, out.stderr
    root = ET.fromstring(out.stdout.encode())
    files = [f.get("name") for f in root.findall("CoSimulation/SourceFiles/File")]
    assert files == ["tribo/a.c", "sundials/b & c.c"]
    generated = open(description, encoding="utf-8").read()
    start, end = out.stdout.index("<SourceFiles>"), out.stdout.index("</CoSimulation>") + len("</CoSimulation>")
    assert out.stdout[:start].rstrip()[:-1] + "/>" + out.stdout[end:] == generated


@pytest.mark.parametrize("case", ["fmi3", "no_files", "source_files_already"])
def test_add_source_files_refuses_what_it_cannot_use(tmp_path, case):
    build = tmp_path / "buildDescription.xml"
    build.write_text('<fmiBuildDescription fmiVersion="3.0"><BuildConfiguration modelIdentifier="x">'
                     '<SourceFileSet><SourceFile name="a.c"/></SourceFileSet></BuildConfiguration>'
                     '</fmiBuildDescription>')
    description = os.path.join(BUILD_DIR, "fmu", "fmi2.xml")
    if case == "fmi3":
        refused(tool("add_source_files.py", os.path.join(BUILD_DIR, "fmu", "fmi3.xml"), build),
                "fmi3.xml", "not an FMI 2.0 description")
    elif case == "no_files":
        build.write_text('<fmiBuildDescription fmiVersion="3.0"/>')
        refused(tool("add_source_files.py", description, build), "lists no SourceFile")
    else:
        once = tmp_path / "once.xml"
        once.write_text(tool("add_source_files.py", description, build).stdout)
        refused(tool("add_source_files.py", once, build), "once.xml", "empty <CoSimulation/>")


def sundials_tree(root, files, members):
    """A made-up SUNDIALS: `files` (paths under src/ and include/, each a one-line file),
    LICENSE, NOTICE, the configured headers, and a static library of objects `members`."""
    for path in files + ["LICENSE", "NOTICE", "config/sundials_config.h", "config/sundials_export.h"]:
        os.makedirs(os.path.dirname(root / path), exist_ok=True)
        (root / path).write_text(f"/* {path} */\n")
    os.makedirs(root / "objects")
    for member in members:
        (root / "objects" / member).write_text("")
    subprocess.run(["ar", "rc", str(root / "lib.a"), *members], cwd=root / "objects", check=True)
    token = root / "instantiation_token.h"
    token.write_text('#define FMU_INSTANTIATION_TOKEN "{0}"\n')
    return ["--prefix", "tribo", "--version", 3, "--token", token, "--sundials", root,
            "--sundials-config", root / "config", "--sundials-library", root / "lib.a"]


def test_make_sources_lays_out_the_folder_for_one_include_directory(tmp_path):
    args = sundials_tree(tmp_path / "s", ["src/cvode/cvode.c", "src/cvode/cvode_impl.h",
                                          "src/sundials/sundials_math.c", "src/sundials/sundials_debug.h",
                                          "include/cvode/cvode.h", "include/sundials/sundials_types.h",
                                          "include/sundials/sundials_base.hpp", "include/arkode/arkode.h"],
                         ["cvode.c.obj", "sundials_math.c.obj"])
    out = tool("make_sources.py", *args, "--out", tmp_path / "sources")
    assert out.returncode == 0, out.stderr
    made = {os.path.relpath(os.path.join(d, f), tmp_path / "sources")
            for d, _, fs in os.walk(tmp_path / "sources") for f in fs}
    assert {"sundials/cvode.c", "sundials/cvode_impl.h", "sundials/sundials_math.c",
            "sundials/sundials_debug.h", "sundials/sundials_types.h", "sundials/sundials_config.h",
            "sundials/LICENSE", "cvode/cvode.h", "tribo/model.c", "tribo/fmi3.c", "tribo/LICENSE",
            "tribo/variables_model.c", "tribo/variables_impl.h", "tribo/instantiation_token.h",
            "buildDescription.xml"} <= made
    # no other FMI version's, front end's or module's files, no C++ interfaces
    assert not made & {"tribo/fmi2.c", "tribo/front_end_si.c", "tribo/variables_si.c",
                       "arkode/arkode.h", "sundials/sundials_base.hpp"}
    build = ET.parse(tmp_path / "sources" / "buildDescription.xml").getroot()
    listed = [f.get("name") for f in build.iter("SourceFile")]
    assert sorted(listed) == sorted(p for p in made if p.endswith(".c"))


def test_make_sources_lays_out_only_what_the_link_maps_name(tmp_path):
    """With the linker's maps of the binaries, the C files of the core and of SUNDIALS are
    those of the members some map names (a member of any other library is not looked at);
    the headers and this FMU's files of the FMI layer stay."""
    args = sundials_tree(tmp_path / "s", ["src/cvode/cvode.c", "src/cvode/cvode_diag.c",
                                          "src/sundials/sundials_math.c", "include/cvode/cvode.h"],
                         ["cvode.c.obj", "cvode_diag.c.obj", "sundials_math.c.obj"])
    linux, windows = tmp_path / "linux.map", tmp_path / "windows.map"
    linux.write_text("Archive member included to satisfy reference by file (symbol)\n\n"
                     "build/libtribo_core.a(model.c.o)\n    fmu/step.c.o (tribo_create)\n"
                     "build/libtribo_core.a(geometry.c.o)\n    build/libtribo_core.a(model.c.o) (x)\n"
                     "sundials/lib.a(cvode.c.obj)\n    build/libtribo_core.a(model.c.o) (CVodeCreate)\n"
                     "lib/libm.a(e_exp.o)\n")
    windows.write_text("build-win64/libtribo_core.a(model.c.obj)\nsundials/lib.a(sundials_math.c.obj)\n"
                       "mingw/libkernel32.a(libkernel32s01409.o)\n")
    out = tool("make_sources.py", *args, "--out", tmp_path / "sources", "--link-map", linux,
               "--link-map", windows)
    assert out.returncode == 0, out.stderr
    build = ET.parse(tmp_path / "sources" / "buildDescription.xml").getroot()
    listed = {f.get("name") for f in build.iter("SourceFile")}
    layer = {"tribo/logging.c", "tribo/lifecycle.c", "tribo/step.c", "tribo/access.c",
             "tribo/fmu_state.c", "tribo/variables_model.c", "tribo/front_end_model.c",
             "tribo/front_end_chute.c", "tribo/front_end_identity.c", "tribo/fmi3.c"}
    assert listed == layer | {"tribo/model.c", "tribo/geometry.c", "sundials/cvode.c",
                              "sundials/sundials_math.c"}
    made = {os.path.relpath(os.path.join(d, f), tmp_path / "sources")
            for d, _, fs in os.walk(tmp_path / "sources") for f in fs}
    assert {p for p in made if p.endswith(".c")} == listed
    assert {"tribo/model.h", "tribo/quantities.def", "cvode/cvode.h"} <= made


@pytest.mark.parametrize("case", ["no_core", "unknown_core_file", "unreadable"])
def test_make_sources_refuses_a_link_map_it_cannot_use(tmp_path, case):
    args = sundials_tree(tmp_path / "s", ["src/cvode/cvode.c", "include/cvode/cvode.h"],
                         ["cvode.c.obj"])
    link_map = tmp_path / "binary.map"
    link_map.write_text({"no_core": "sundials/lib.a(cvode.c.obj)\n",
                         "unknown_core_file": "build/libtribo_core.a(elsewhere.c.o)\n",
                         "unreadable": ""}[case])
    if case == "unreadable":
        link_map = tmp_path / "absent.map"
    out = tool("make_sources.py", *args, "--out", tmp_path / "sources", "--link-map", link_map)
    words = {"no_core": ["binary.map", "names no member of libtribo_core.a"],
             "unknown_core_file": ["elsewhere.c", "not a C file of src/"],
             "unreadable": ["cannot read the link map", "absent.map"]}[case]
    refused(out, *words)


@pytest.mark.parametrize("case", ["twice_in_sundials", "same_header_in_two_folders", "missing_library"])
def test_make_sources_refuses_what_it_cannot_lay_out(tmp_path, case):
    files = ["src/cvode/cvode.c", "include/cvode/cvode.h"]
    members = ["cvode.c.obj"]
    if case == "twice_in_sundials":
        files.append("src/cvodes/cvode.c")
    if case == "same_header_in_two_folders":
        files += ["src/cvode/shared.h", "src/nvector/serial/nvector_serial.c", "src/nvector/serial/shared.h"]
        members.append("nvector_serial.c.obj")
    args = sundials_tree(tmp_path / "s", files, members)
    if case == "missing_library":
        args[-1] = tmp_path / "none.a"
    out = tool("make_sources.py", *args, "--out", tmp_path / "sources")
    words = {"twice_in_sundials": ["cvode.c", "2 times"],
             "same_header_in_two_folders": ["sundials/shared.h", "would come from both"],
             "missing_library": ["cannot list", "none.a"]}[case]
    refused(out, *words)
