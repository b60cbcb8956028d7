"""Writes the FMI 3.0 buildDescription.xml of a source FMU's sources/ folder (also packed
into the FMI 2.0 FMU, whose importers ignore it): every C file to compile, the include
directories, the preprocessor definitions. Compiling the listed files into a shared
library (and linking the C maths library on Unix) gives the FMU's binary.

    python build_description.py <tribo|tribo_si> <2|3> <sources folder> > buildDescription.xml

The first argument is the FMU pair's prefix (its modelIdentifier is <prefix>_fmi<version>).
"""

import os
import sys
from xml.sax.saxutils import quoteattr

DEFINITIONS = [
    ("_DEFAULT_SOURCE", "M_PI and the POSIX names under C11 (glibc)"),
    ("_USE_MATH_DEFINES", "M_PI on Windows"),
    ("SUNDIALS_STATIC_DEFINE", "SUNDIALS compiled into the FMU's binary, not imported"),
]


def main():
    prefix, version, folder = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    definitions = DEFINITIONS
    sources, includes = [], set()
    for directory, _, files in sorted(os.walk(folder)):
        relative = os.path.relpath(directory, folder).replace(os.sep, "/")
        for name in sorted(files):
            if name.endswith(".c"):
                sources.append(f"{relative}/{name}")
            elif name.endswith(".h") and relative != ".":
                includes.add(relative)
    # public SUNDIALS headers are included as <sundials/...>, <cvode/...>, ...
    includes = {i for i in includes if not i.startswith("sundials/include/")} | {"sundials/include"}
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<fmiBuildDescription fmiVersion="3.0">',
           f'  <BuildConfiguration modelIdentifier="{prefix}_fmi{version}" '
           f'description="the FMU as one shared library (link the C maths library on Unix)">',
           '    <SourceFileSet language="C11">']
    out += [f"      <SourceFile name={quoteattr(s)}/>" for s in sources]
    out += [f"      <PreprocessorDefinition name={quoteattr(n)} description={quoteattr(d)}/>"
            for n, d in definitions]
    out += [f"      <IncludeDirectory name={quoteattr(i)}/>" for i in sorted(includes)]
    out += ["    </SourceFileSet>", "  </BuildConfiguration>", "</fmiBuildDescription>"]
    print("\n".join(out))


if __name__ == "__main__":
    main()
