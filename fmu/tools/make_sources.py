"""Lays out the sources/ folder of a source FMU so that it compiles with nothing but
sources/ (and the importer's own FMI headers) on the include path: what FMPy's build
helper (`fmpy compile`) and most importers give the compiler, whatever buildDescription.xml
says.

    python make_sources.py --prefix <tribo|tribo_si|tribo_separator> --version <2|3> --out <folder>
        --token <instantiation_token.h> --sundials <SUNDIALS' source tree>
        --sundials-config <folder with the configured sundials_config.h, sundials_export.h>
        --sundials-library <static library> [--sundials-library ...]
        [--link-map <the linker's map of the FMU's binary> ...]

The layout (fmu/README.md):

    tribo/        the core (every folder of src/) and this FMU's part of the FMI layer (fmu/)
                  in one folder, where their quoted includes find each other (they include
                  each other by file name), and the project's licence
    sundials/     SUNDIALS' <sundials/...> headers with the configured ones; the
                  implementation of every object of the given static libraries (its .c
                  files and the private headers beside them), flattened into this one
                  folder because those files include each other's private headers by
                  quotes across SUNDIALS' own source folders; SUNDIALS' LICENSE and NOTICE
    cvode/, nvector/, sunlinsol/, ...   the public headers of the other SUNDIALS modules
                  compiled in, where <cvode/cvode.h> and the like resolve
    buildDescription.xml   (build_description.py) the files to compile

With --link-map (the GNU linker's -Map of each binary the FMU ships: fmu/CMakeLists.txt
writes them), the C files of the core and of SUNDIALS are only those whose objects one of
the binaries links: what the FMU runs, without the parts of SUNDIALS it never calls (the
Krylov solvers, band and sparse matrices) or the core of another FMU (the separator's FMUs
hold none of the chute), so that an importer compiles no more than that. Headers are kept
whole.

Every C file in the folder is one to compile. Any two files that would land on the same
path are an error, not an overwrite.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys

from build_description import build_description

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# tribo_fmu_layer in fmu/CMakeLists.txt, and each front end's object library
FMU_LAYER = ["logging.c", "lifecycle.c", "step.c", "access.c", "fmu_state.c"]
FRONT_END = {"tribo": ["variables_model.c", "front_end_model.c", "front_end_chute.c",
                       "front_end_identity.c"],
             "tribo_si": ["variables_si.c", "front_end_si.c", "front_end_chute.c"],
             "tribo_separator": ["variables_separator.c", "front_end_separator.c",
                                 "front_end_identity.c"]}
# configured by SUNDIALS' CMake for the Windows build (static: SUNDIALS_EXPORT is empty);
# of what they hold only the deprecation attributes are compiler-specific (a __declspec, a
# GCC attribute): made empty, so that any C compiler takes them
SUNDIALS_CONFIGURED = ["sundials_config.h", "sundials_export.h"]
COMPILER_SPECIFIC = ["__declspec(deprecated(msg))", "__attribute__ ((__deprecated__))"]


class Layout:
    """The files of the folder being made, refusing a second file on the same path."""

    def __init__(self, out):
        self.out = out
        self.origin = {}

    def add(self, relative, source, text=None):
        if relative in self.origin:
            sys.exit(f"make_sources: {relative} would come from both {self.origin[relative]} "
                     f"and {source}")
        self.origin[relative] = source
        target = os.path.join(self.out, relative)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        if text is None:
            shutil.copyfile(source, target)
        else:
            with open(target, "w", encoding="utf-8", newline="\n") as f:
                f.write(text)


CORE_LIBRARY = "libtribo_core.a"
# a member of a static library as a GNU linker's map (ld's or lld's) names it: lib.a(member)
MAP_MEMBER = re.compile(r"([^\s()]+\.a)\(([^\s()]+)\)")


def c_file_of(member, library):
    """The C file an object of a static library was compiled from (members `<file>.c.obj`
    or `<file>.c.o`)."""
    stem, _ = os.path.splitext(member)
    if not stem.endswith(".c"):
        sys.exit(f"make_sources: {library}: member {member} is not an object of a C file")
    return stem


def linked_members(maps):
    """{static library's file name: the file names, less the object's extension, of its
    members that the binaries link (for the core's and SUNDIALS' libraries, the C files
    they were compiled from)}, from their linker maps; None without maps (every member is
    linked)."""
    if not maps:
        return None
    linked = {}
    for path in maps:
        try:
            with open(path, encoding="utf-8", errors="replace") as f:
                found = MAP_MEMBER.findall(f.read())
        except OSError as e:
            sys.exit(f"make_sources: cannot read the link map {path}: {e.strerror}")
        if not any(os.path.basename(library) == CORE_LIBRARY for library, _ in found):
            sys.exit(f"make_sources: {path} names no member of {CORE_LIBRARY}: not the map of "
                     f"an FMU's link")
        for library, member in found:
            linked.setdefault(os.path.basename(library), set()).add(os.path.splitext(member)[0])
    return linked


def library_objects(libraries, linked=None):
    """The C files SUNDIALS' static libraries were compiled from, each once: every member's,
    or with linked (linked_members) those the binaries link."""
    names = set()
    for library in libraries:
        listing = subprocess.run(["ar", "t", library], capture_output=True, text=True)
        if listing.returncode != 0:
            sys.exit(f"make_sources: cannot list {library}: {listing.stderr.strip()}")
        members = {c_file_of(member, library) for member in listing.stdout.split()}
        if linked is not None:
            members &= linked.get(os.path.basename(library), set())
        names |= members
    return sorted(names)


def sundials_files(tree, names):
    """{file name: path relative to SUNDIALS' src/} of the named C files, each of which
    must be there exactly once."""
    found = {}
    for folder, _, files in os.walk(os.path.join(tree, "src")):
        for name in set(files) & set(names):
            found.setdefault(name, []).append(os.path.relpath(os.path.join(folder, name),
                                                              os.path.join(tree, "src")))
    for name in names:
        if len(found.get(name, [])) != 1:
            sys.exit(f"make_sources: {name} is in SUNDIALS' src/ {len(found.get(name, []))} "
                     f"times; it must be there once")
    return {name: paths[0] for name, paths in found.items()}


def core_files():
    """The core's C files, headers and tables, every folder of src/ (paths from the root)."""
    files = []
    for folder, _, names in sorted(os.walk(os.path.join(ROOT, "src"))):
        relative = os.path.relpath(folder, ROOT).replace(os.sep, "/")
        files += [f"{relative}/{f}" for f in sorted(names) if f.endswith((".c", ".h", ".def"))]
    return files


def add_tribo(layout, prefix, version, token, linked=None):
    core = core_files()
    compiled = [f for f in core if f.endswith(".c")]
    if linked is not None:
        wanted = linked.get(CORE_LIBRARY, set())
        unknown = wanted - {os.path.basename(f) for f in compiled}
        if unknown:
            sys.exit(f"make_sources: the link map names {' '.join(sorted(unknown))} of "
                     f"{CORE_LIBRARY}, not a C file of src/")
        compiled = [f for f in compiled if os.path.basename(f) in wanted]
    compiled += [f"fmu/{f}" for f in FMU_LAYER + FRONT_END[prefix] + [f"fmi{version}.c"]]
    other = [f for f in core if f.endswith((".h", ".def"))]
    other += [f"fmu/{f}" for f in sorted(os.listdir(os.path.join(ROOT, "fmu"))) if f.endswith(".h")]
    for path in compiled + other:
        layout.add(f"tribo/{os.path.basename(path)}", os.path.join(ROOT, path))
    layout.add("tribo/instantiation_token.h", token)
    layout.add("tribo/LICENSE", os.path.join(ROOT, "LICENSE"))
    return [f"tribo/{os.path.basename(path)}" for path in compiled]


def add_sundials(layout, tree, config, libraries, linked=None):
    files = sundials_files(tree, library_objects(libraries, linked))
    compiled = []
    for name, path in sorted(files.items()):
        layout.add(f"sundials/{name}", os.path.join(tree, "src", path))
        compiled.append(f"sundials/{name}")
    # the private headers of every folder compiled from, beside the C files
    for folder in sorted({os.path.dirname(p) for p in files.values()}):
        for header in sorted(os.listdir(os.path.join(tree, "src", folder))):
            if header.endswith(".h"):
                layout.add(f"sundials/{header}", os.path.join(tree, "src", folder, header))
    # the public headers of every module compiled from (src/<module>/... -> include/<module>)
    for module in sorted({p.split(os.sep)[0] for p in files.values()}):
        include = os.path.join(tree, "include", module)
        for folder, _, headers in sorted(os.walk(include)):
            for header in sorted(headers):
                relative = os.path.relpath(os.path.join(folder, header), include).replace(os.sep, "/")
                if relative.endswith(".h"):  # not the C++ interfaces (.hpp)
                    layout.add(f"{module}/{relative}", os.path.join(folder, header))
    for name in SUNDIALS_CONFIGURED:
        with open(os.path.join(config, name), encoding="utf-8") as f:
            text = f.read()
        for attribute in COMPILER_SPECIFIC:
            text = text.replace(attribute, "")
        layout.add(f"sundials/{name}", os.path.join(config, name), text)
    for name in ("LICENSE", "NOTICE"):
        layout.add(f"sundials/{name}", os.path.join(tree, name))
    return compiled


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--prefix", required=True, choices=sorted(FRONT_END))
    parser.add_argument("--version", required=True, type=int, choices=(2, 3))
    parser.add_argument("--out", required=True)
    parser.add_argument("--token", required=True)
    parser.add_argument("--sundials", required=True)
    parser.add_argument("--sundials-config", required=True)
    parser.add_argument("--sundials-library", required=True, action="append")
    parser.add_argument("--link-map", action="append", default=[])
    args = parser.parse_args()

    linked = linked_members(args.link_map)
    shutil.rmtree(args.out, ignore_errors=True)
    layout = Layout(args.out)
    try:
        compiled = add_tribo(layout, args.prefix, args.version, args.token, linked)
        compiled += add_sundials(layout, args.sundials, args.sundials_config, args.sundials_library,
                                 linked)
    except OSError as e:
        sys.exit(f"make_sources: {e}")
    # every C file there is one to compile: `cc sources/*/*.c` is the build (fmu/README.md)
    stray = sorted(p for p in layout.origin if p.endswith(".c") and p not in compiled)
    if stray:
        sys.exit(f"make_sources: C files that are not compiled: {' '.join(stray)}")
    layout.add("buildDescription.xml", __file__,
               build_description(f"{args.prefix}_fmi{args.version}", sorted(compiled)))


if __name__ == "__main__":
    main()
