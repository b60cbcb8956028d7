"""Writes an FMI 2.0 modelDescription with the <SourceFiles> of its source FMU: FMI 2.0
importers read the files to compile from there (buildDescription.xml is FMI 3.0's). The
list is the one of the FMU's sources/buildDescription.xml (make_sources.py).

    python add_source_files.py <generated fmi2 description> <sources/buildDescription.xml> > out.xml

The generated description is left as it is, byte for byte, but for the element added to
its <CoSimulation>: the instantiation token, a hash of the generated description, stays
the one the binaries carry. The build's own FMUs, which have no sources/, and the reviewed
copies in modelDescription/ are the generated descriptions without it.
"""

import re
import sys
import xml.etree.ElementTree as ET
from xml.sax.saxutils import quoteattr


def with_source_files(description, files):
    """The FMI 2.0 description text with <SourceFiles> listing `files` in its (empty)
    <CoSimulation/> element."""
    empty = list(re.finditer(r"(\n(\s*)<CoSimulation\b[^>]*?)\s*/>", description))
    if len(empty) != 1 or 'fmiVersion="2.0"' not in description:
        raise ValueError("not an FMI 2.0 description with one empty <CoSimulation/> element")
    start, indent = empty[0].group(1), empty[0].group(2)
    step = "  "
    lines = [f"{start}>", f"{indent}{step}<SourceFiles>"]
    lines += [f"{indent}{step * 2}<File name={quoteattr(f)}/>" for f in files]
    lines += [f"{indent}{step}</SourceFiles>", f"{indent}</CoSimulation>"]
    return description[:empty[0].start()] + "\n".join(lines) + description[empty[0].end():]


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: " + __doc__.split("\n\n")[1].strip())
    try:
        with open(sys.argv[1], encoding="utf-8", newline="") as f:
            description = f.read()
        files = [s.get("name") for s in ET.parse(sys.argv[2]).getroot().iter("SourceFile")]
    except OSError as e:
        sys.exit(f"add_source_files: {e}")
    except ET.ParseError as e:
        sys.exit(f"add_source_files: {sys.argv[2]}: {e}")
    if not files:
        sys.exit(f"add_source_files: {sys.argv[2]} lists no SourceFile")
    try:
        text = with_source_files(description, files)
    except ValueError as e:
        sys.exit(f"add_source_files: {sys.argv[1]}: {e}")
    sys.stdout.buffer.write(text.encode("utf-8"))


if __name__ == "__main__":
    main()
