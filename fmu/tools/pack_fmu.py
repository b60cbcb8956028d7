"""Packs a tribo .fmu: the modelDescription, the binaries of each platform, the
documentation (documentation/index.html, generated from the project's model
documentation and the description's variable table, and the licences in
documentation/licenses/) and, for a source FMU, sources/. The archive is reproducible:
its entries are sorted and dated SOURCE_DATE_EPOCH (the description's own date).

    python pack_fmu.py --out tribo_fmi3.fmu --description fmi3.xml --model-doc docs/model.md \
        --binary x86_64-linux=build/fmu/lib/tribo_fmi3.so --binary x86_64-windows=...dll \
        --license license.txt=LICENSE --license SUNDIALS-LICENSE=<sundials>/LICENSE \
        [--sources <folder>] [--epoch 1700000000]
"""

import argparse
import html
import os
import time
import xml.etree.ElementTree as ET
import zipfile

import markdown


def variable_rows(root, version):
    """(name, value reference, causality, variability, type, unit, range, start,
    description) of every variable, as the description declares them."""
    rows = []
    for element in root.find("ModelVariables"):
        a = dict(element.attrib)
        if version == 2:
            kind = element[0]
            a.update(kind.attrib)
            type_name = kind.tag
        else:
            type_name = element.tag
        if "declaredType" in a:
            type_name += f" ({a['declaredType']})"
        unit = a.get("unit", "")
        if a.get("displayUnit"):
            unit += f" (shown in {a['displayUnit']})"
        bounds = [f"&ge; {a['min']}" if "min" in a else "", f"&le; {a['max']}" if "max" in a else ""]
        rows.append((a["name"], a["valueReference"], a.get("causality", "local"),
                     a.get("variability", ""), type_name, unit,
                     ", ".join(b for b in bounds if b), a.get("start", ""), a.get("description", "")))
    return rows


def enumeration_rows(root, version):
    """(type name, item name, value, description) of every enumeration item."""
    types = root.find("TypeDefinitions")
    rows = []
    for t in (types if types is not None else []):
        items = t.find("Enumeration") if version == 2 else t
        for item in items.findall("Item"):
            rows.append((t.get("name"), item.get("name"), item.get("value"), item.get("description", "")))
    return rows


def table(header, rows, raw_columns=()):
    def cell(i, value):
        return value if i in raw_columns else html.escape(value)
    out = ["<table>", "<tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in header) + "</tr>"]
    for row in rows:
        out.append("<tr>" + "".join(f"<td>{cell(i, v)}</td>" for i, v in enumerate(row)) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def documentation(description_xml, model_doc, licenses):
    """documentation/index.html: the FMU's metadata, the model and every variable."""
    root = ET.fromstring(description_xml)
    version = int(root.get("fmiVersion")[0])
    with open(model_doc, encoding="utf-8") as f:
        model = markdown.markdown(f.read(), extensions=["tables", "fenced_code"])
    meta = [(key, root.get(key, "")) for key in ("modelName", "description", "version", "author",
                                                  "copyright", "license", "generationTool",
                                                  "generationDateAndTime")]
    meta.append(("fmiVersion", root.get("fmiVersion")))
    license_links = ", ".join(f'<a href="licenses/{html.escape(n)}">{html.escape(n)}</a>'
                              for n in licenses)
    title = html.escape(f"{root.get('modelName')} {root.get('version')} (FMI {root.get('fmiVersion')})")
    return f"""<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<title>{title}</title>
<style>
body {{ font-family: sans-serif; max-width: 70em; margin: 1em auto; padding: 0 1em; }}
table {{ border-collapse: collapse; font-size: 90%; }}
td, th {{ border: 1px solid #bbb; padding: 0.2em 0.4em; vertical-align: top; text-align: left; }}
</style>
</head>
<body>
<h1>{title}</h1>
{table(["", ""], meta)}
<p>Licences: {license_links}.</p>
<h2>Variables</h2>
<p>Every variable of this FMU as its modelDescription.xml declares it (ranges are inclusive;
everything is dimensionless but angles, see the model).</p>
{table(["name", "value reference", "causality", "variability", "type", "unit", "range", "start",
        "description"], variable_rows(root, version), raw_columns=(6,))}
<h2>Enumerations</h2>
{table(["type", "item", "value", "description"], enumeration_rows(root, version))}
<h2>The model</h2>
{model}
</body>
</html>
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True)
    parser.add_argument("--description", required=True)
    parser.add_argument("--model-doc", required=True)
    parser.add_argument("--binary", action="append", default=[], help="PLATFORM=FILE")
    parser.add_argument("--license", action="append", default=[], help="NAME=FILE")
    parser.add_argument("--sources", help="a folder packed as sources/")
    parser.add_argument("--epoch", type=int,
                        default=int(os.environ.get("SOURCE_DATE_EPOCH", "315532800")))
    args = parser.parse_args()

    with open(args.description, "rb") as f:
        description = f.read()
    model_identifier = ET.fromstring(description).find("CoSimulation").get("modelIdentifier")
    entries = {"modelDescription.xml": description}
    for spec in args.binary:
        platform, path = spec.split("=", 1)
        with open(path, "rb") as f:
            entries[f"binaries/{platform}/{model_identifier}{os.path.splitext(path)[1]}"] = f.read()
    licenses = {}
    for spec in args.license:
        name, path = spec.split("=", 1)
        with open(path, "rb") as f:
            licenses[name] = f.read()
            entries[f"documentation/licenses/{name}"] = licenses[name]
    page = documentation(description, args.model_doc, licenses).encode()
    entries["documentation/index.html"] = page
    if ET.fromstring(description).get("fmiVersion") == "2.0":
        entries["documentation/_main.html"] = page  # FMI 2.0's entry point
    if args.sources:
        for folder, _, files in os.walk(args.sources):
            for name in files:
                path = os.path.join(folder, name)
                with open(path, "rb") as f:
                    entries["sources/" + os.path.relpath(path, args.sources).replace(os.sep, "/")] = f.read()

    # zip dates start in 1980
    date = time.gmtime(max(args.epoch, 315532800))[:6]
    tmp = args.out + ".tmp"
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        for name in sorted(entries):
            info = zipfile.ZipInfo(name, date_time=date)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, entries[name])
    os.replace(tmp, args.out)


if __name__ == "__main__":
    main()
