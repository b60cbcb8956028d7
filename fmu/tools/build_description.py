"""The FMI 3.0 buildDescription.xml of a source FMU's sources/ folder (make_sources.py
writes it there; add_source_files.py copies its list into an FMI 2.0 description): the C
files to compile into the FMU's one shared library. They need no include directory but
sources/ itself and the importer's FMI headers, and no preprocessor definition with a C
compiler in its default mode; the two definitions listed are for compilers in strict ISO
mode (M_PI)."""

from xml.sax.saxutils import quoteattr

# value "1": an importer that passes NAME=<value> (FMPy) gets a value it can write
DEFINITIONS = [
    ("_DEFAULT_SOURCE", "M_PI with glibc under a strict -std=c11 (the GNU modes define it)"),
    ("_USE_MATH_DEFINES", "M_PI with Microsoft's C library"),
]
LIBRARY = ("m", "the C maths library, on Unix (the importer's: part of the C library elsewhere)")


def build_description(model_identifier, sources):
    """The description of one build configuration compiling `sources` (paths relative to
    sources/, in order)."""
    out = ['<?xml version="1.0" encoding="UTF-8"?>',
           '<fmiBuildDescription fmiVersion="3.0">',
           f'  <BuildConfiguration modelIdentifier={quoteattr(model_identifier)} '
           f'description="the FMU as one shared library">',
           '    <SourceFileSet language="C11">']
    out += [f"      <SourceFile name={quoteattr(s)}/>" for s in sources]
    out += [f'      <PreprocessorDefinition name={quoteattr(n)} value="1" optional="true" '
            f'description={quoteattr(d)}/>' for n, d in DEFINITIONS]
    out += ["    </SourceFileSet>",
            f'    <Library name={quoteattr(LIBRARY[0])} external="true" '
            f'description={quoteattr(LIBRARY[1])}/>',
            "  </BuildConfiguration>", "</fmiBuildDescription>"]
    return "\n".join(out) + "\n"
