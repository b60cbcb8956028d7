"""The separation line as an SSP 1.0 package (docs/separator.md, "The SSP package"): the SI
chute's FMU feeding the free-fall separator's, for any SSP importer (libcosim, ecos,
OMSimulator, ...).

    tribo_line.ssp
        SystemStructure.ssd          the system: two components, their connectors (with
                                     types and units), the four connections, the parameter
                                     bindings and the default experiment
        resources/tribo_si_fmi2.fmu, resources/tribo_separator_fmi2.fmu   the FMUs as built
        resources/chute.ssv, resources/separator.ssv   the parameter set "line", one file a
                                     component, names unprefixed

    from tribo.ssp import build
    build("build/ssp/tribo_line.ssp", "build/fmu/tribo_si_fmi2.fmu",
          "build/fmu/tribo_separator_fmi2.fmu")

The build makes build/ssp/tribo_line.ssp with the FMUs (fmu/CMakeLists.txt, through
fmu/tools/pack_ssp.py). Only the standard library: the XML is made with xml.etree, the types
and units of the connectors are read from the FMUs' own modelDescriptions.

Why these choices:
- The connection carries the static charge model's ratio (charge_to_mass_model = 1, an FMI
  Integer that every importer sets): the chute's output charge_to_mass is the one model's
  that parameter names, the models being alternative laws of the same grain's charge
  (docs/model.md §5). The charge-model switches (FMI Enumerations) are left at their
  defaults, both on: libcosim and ecos set no FMI 2.0 Enumeration.
- Both components hold at their run's end (hold_at_end = true): the chute's exit and the
  separator's landing would otherwise end the step with fmi2Discard and fmi2Terminated,
  which libcosim takes for a failed step and ends the whole execution on.
- The parameters the two FMUs share (tilt, semi_major_axis, epsilon, density) are written
  from one value into both files.
- One .ssv a component, its names unprefixed, bound without `prefix`: libcosim and ecos apply
  a set's names to the component the binding is on and ignore `prefix`.
- An FMI Enumeration parameter, if one is given, is written as ssv:Integer, its value: an
  ssv:Enumeration aborts libcosim (libcosimpy 0.0.6: "ssp_parser.cpp:69: Internal error")
  and ecos (0.7.2) refuses the package ("Unknown XML node in ssv:Parameter encountered!");
  neither tool sets FMI 2.0 Enumeration variables at all (docs/separator.md).
- The default experiment carries OSP's fixed-step annotation (libcosim's step when none is
  given).
"""

import io
import math
import os
import time
import xml.etree.ElementTree as ET
import zipfile

NAMESPACES = {
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
    # libcosim's annotation of the default experiment (its fixed step)
    "osp": "http://opensimulationplatform.com/SSP/OSPAnnotations",
}
for _prefix, _uri in NAMESPACES.items():
    # libcosim's and ecos' SSP readers match the prefixes literally: these, and no others
    ET.register_namespace(_prefix, _uri)

CHUTE, SEPARATOR = "chute", "separator"
# the chute's outputs -> the separator's inputs (docs/separator.md, "Coupling with the SI chute")
CONNECTIONS = (("exited", "released"), ("u", "u_entry"), ("v", "v_entry"),
               ("charge_to_mass", "charge_to_mass"))
# outputs shown as the components' connectors beside the connected ones: what a user reads
# (and the chute's charge_to_mass_<model> of each charge model it has: `observed`)
OBSERVED = {CHUTE: ("exit_time",),
            SEPARATOR: ("has_released", "ended", "landed", "bin", "x_end", "z_end",
                        "flight_time", "q_per_m")}
# a charge model <name> of the chute: its switch charge_model_<name>, its ratio charge_to_mass_<name>
SWITCH_PREFIX, CHARGE_TO_MASS_PREFIX = "charge_model_", "charge_to_mass_"
# bound to one value in both components (the FMUs' defaults: a 1 mm polyethylene grain,
# epsilon 0.6, on a chute tilted 30 degrees)
SHARED = {"tilt": math.radians(30), "semi_major_axis": 5e-4, "epsilon": 0.6, "density": 950.0}
# a 0.3 m chute carrying the static model's ratio, held at its exit (above)
CHUTE_PARAMETERS = {"chute_length": 0.3, "charge_to_mass_model": 1, "hold_at_end": True}
# the separator's defaults (0.1 m gap, 0.5 m high, 30 kV, 10 bins), held at its landing
SEPARATOR_PARAMETERS = {"hold_at_end": True}
PARAMETER_SET = "line"
# the grain leaves the 0.3 m chute at 0.48 s and lands 0.36 s later (measured,
# tests/python/test_ssp.py): 1.5 s leaves room for other set-ups
START_TIME, STOP_TIME, STEP_SIZE = 0.0, 1.5, 1e-3
SSD_NAME = "SystemStructure.ssd"

# an FMU variable's type -> the SSP connector type (FMI 2.0 and 3.0 names)
_SSC_TYPE = {"Real": "Real", "Float64": "Real", "Float32": "Real", "Integer": "Integer",
             "Int32": "Integer", "Boolean": "Boolean", "String": "String",
             "Enumeration": "Enumeration"}


def _q(prefix, tag):
    return f"{{{NAMESPACES[prefix]}}}{tag}"


def _sub(parent, prefix, tag, **attributes):
    return ET.SubElement(parent, _q(prefix, tag), {k: v for k, v in attributes.items()
                                                   if v is not None})


def _number(value):
    return repr(float(value))


class Variable:
    """One variable of an FMU's modelDescription: name, causality, type (the FMI type's
    element name), unit (or None) and the unit's base-unit exponents."""

    def __init__(self, name, causality, type_name, unit, base_unit):
        self.name, self.causality, self.type = name, causality, type_name
        self.unit, self.base_unit = unit, base_unit

    @property
    def ssc_type(self):
        return _SSC_TYPE[self.type]


def read_model_description(fmu):
    """The variables of an .fmu (FMI 2.0 or 3.0) by name, and its FMI version's major
    number, from its modelDescription.xml."""
    with zipfile.ZipFile(fmu) as z:
        root = ET.fromstring(z.read("modelDescription.xml"))
    version = int(root.get("fmiVersion").split(".")[0])
    units = {}
    for unit in root.findall("UnitDefinitions/Unit"):
        base = unit.find("BaseUnit")
        units[unit.get("name")] = dict(base.attrib) if base is not None else {}
    variables = {}
    for element in root.find("ModelVariables"):
        if version == 2:
            kind = element[0]
            type_name, unit = kind.tag, kind.get("unit")
        else:
            type_name, unit = element.tag, element.get("unit")
        variables[element.get("name")] = Variable(element.get("name"),
                                                  element.get("causality", "local"), type_name,
                                                  unit, units.get(unit, {}) if unit else None)
    return variables, version


def _units(parent, variables):
    """ssc:Unit definitions of the variables' units (their BaseUnit exponents as the FMU
    declares them) into `parent` (an ssd:Units or ssv:Units)."""
    seen = {}
    for v in variables:
        if v.unit is not None:
            seen.setdefault(v.unit, v.base_unit)
    for name in sorted(seen):
        _sub(_sub(parent, "ssc", "Unit", name=name), "ssc", "BaseUnit", **seen[name])


def parameter_values(values, variables, name=PARAMETER_SET):
    """An ssv:ParameterSet of `values` (name -> value) for a component whose modelDescription
    gave `variables`: each must be a parameter of the FMU; Real with its unit, Integer,
    Boolean, and an Enumeration written as its integer value (see the module's notes)."""
    root = ET.Element(_q("ssv", "ParameterSet"), {"version": "1.0", "name": name})
    parameters = _sub(root, "ssv", "Parameters")
    used = []
    for key, value in values.items():
        v = variables.get(key)
        if v is None or v.causality != "parameter":
            raise ValueError(f"{key} is not a parameter of the FMU")
        p = _sub(parameters, "ssv", "Parameter", name=key)
        if v.ssc_type == "Real":
            _sub(p, "ssv", "Real", value=_number(value), unit=v.unit)
            used.append(v)
        elif v.ssc_type in ("Integer", "Enumeration"):
            if int(value) != value:
                raise ValueError(f"{key} = {value!r}: an integer is needed")
            _sub(p, "ssv", "Integer", value=str(int(value)))
        elif v.ssc_type == "Boolean":
            _sub(p, "ssv", "Boolean", value="true" if value else "false")
        else:
            _sub(p, "ssv", "String", value=str(value))
    if any(v.unit for v in used):
        _units(_sub(root, "ssv", "Units"), used)
    return root


def system_structure(chute, separator, *, chute_source, separator_source, chute_ssv,
                     separator_ssv, start_time=START_TIME, stop_time=STOP_TIME,
                     step_size=STEP_SIZE):
    """The ssd:SystemStructureDescription of the line. chute and separator: their
    variables (read_model_description); *_source: the FMUs' paths in the package; *_ssv:
    their .ssv files' paths in the package. Each connection joins an output to an input of
    one type and one unit, or ValueError says which does not."""
    for src, dst in CONNECTIONS:
        a, b = chute.get(src), separator.get(dst)
        if a is None or b is None:
            raise ValueError(f"connection {CHUTE}.{src} -> {SEPARATOR}.{dst}: no such variable")
        if (a.causality, b.causality) != ("output", "input"):
            raise ValueError(f"connection {CHUTE}.{src} -> {SEPARATOR}.{dst}: "
                             f"{a.causality} -> {b.causality}, not output -> input")
        if a.ssc_type != b.ssc_type or a.unit != b.unit or a.base_unit != b.base_unit:
            raise ValueError(f"connection {CHUTE}.{src} -> {SEPARATOR}.{dst}: "
                             f"{a.type} [{a.unit}] -> {b.type} [{b.unit}]")
    connected = {CHUTE: [s for s, _ in CONNECTIONS], SEPARATOR: [d for _, d in CONNECTIONS]}

    root = ET.Element(_q("ssd", "SystemStructureDescription"),
                      {"version": "1.0", "name": "tribo_line",
                       "description": "the SI chute's FMU feeding the free-fall separator's "
                                      "(tribo, docs/separator.md)"})
    system = _sub(root, "ssd", "System", name="line",
                  description="a charged grain leaves the chute and falls between the "
                              "separator's plates into a bin")
    elements = _sub(system, "ssd", "Elements")
    units = []
    for name, variables, source, ssv in ((CHUTE, chute, chute_source, chute_ssv),
                                         (SEPARATOR, separator, separator_source, separator_ssv)):
        component = _sub(elements, "ssd", "Component", name=name,
                         type="application/x-fmu-sharedlibrary", source=source)
        connectors = _sub(component, "ssd", "Connectors")
        for key in connected[name] + observed(name, variables):
            v = variables[key]
            if v.ssc_type == "Enumeration":  # libcosim aborts on an Enumeration connector
                raise ValueError(f"{name}.{key}: an Enumeration connector")
            connector = _sub(connectors, "ssd", "Connector", name=key, kind=v.causality)
            _sub(connector, "ssc", v.ssc_type, unit=v.unit if v.ssc_type == "Real" else None)
            if v.ssc_type == "Real" and v.unit:
                units.append(v)
        bindings = _sub(component, "ssd", "ParameterBindings")
        _sub(bindings, "ssd", "ParameterBinding", type="application/x-ssp-parameter-set",
             source=ssv)
    connections = _sub(system, "ssd", "Connections")
    for src, dst in CONNECTIONS:
        _sub(connections, "ssd", "Connection", startElement=CHUTE, startConnector=src,
             endElement=SEPARATOR, endConnector=dst)
    _units(_sub(root, "ssd", "Units"), units)
    experiment = _sub(root, "ssd", "DefaultExperiment", startTime=_number(start_time),
                      stopTime=_number(stop_time))
    annotation = _sub(_sub(experiment, "ssd", "Annotations"), "ssc", "Annotation",
                      type="com.opensimulationplatform")
    _sub(_sub(annotation, "osp", "Algorithm"), "osp", "FixedStepAlgorithm",
         baseStepSize=_number(step_size))
    return root


def observed(component, variables) -> list[str]:
    """The outputs a component shows beside its connected ones: OBSERVED, and the chute's
    charge-to-mass ratio of each charge model its switches name (fmu/charge_models.py
    reads them the same way; this module keeps to the standard library)."""
    models = [n[len(SWITCH_PREFIX):] for n, v in variables.items()
              if n.startswith(SWITCH_PREFIX)
              and v.causality in ("parameter", "structuralParameter")]
    extra = [CHARGE_TO_MASS_PREFIX + m for m in models] if component == CHUTE else []
    return list(OBSERVED[component]) + [n for n in extra if n in variables]


def _xml(root):
    ET.indent(root)
    buffer = io.BytesIO()
    ET.ElementTree(root).write(buffer, encoding="UTF-8", xml_declaration=True)
    return buffer.getvalue() + b"\n"


def build(out, chute_fmu, separator_fmu, *, shared=None, chute_parameters=None,
          separator_parameters=None, start_time=START_TIME, stop_time=STOP_TIME,
          step_size=STEP_SIZE, epoch=None):
    """Write the line's .ssp to `out` (folders made) from the two .fmu files, which it
    holds as they are. shared: values bound in both components (default SHARED);
    chute_parameters, separator_parameters: each component's own (defaults
    CHUTE_PARAMETERS, SEPARATOR_PARAMETERS); the default experiment's times and OSP fixed
    step in s. The archive is reproducible: its entries are dated `epoch` (default
    $SOURCE_DATE_EPOCH, else 1980-01-01). Returns out."""
    shared = dict(SHARED if shared is None else shared)
    chute, chute_version = read_model_description(chute_fmu)
    separator, separator_version = read_model_description(separator_fmu)
    if chute_version != separator_version:
        raise ValueError(f"FMI {chute_version}.0 chute with an FMI {separator_version}.0 separator")
    resources = {}
    sources = {}
    for name, fmu in ((CHUTE, chute_fmu), (SEPARATOR, separator_fmu)):
        sources[name] = f"resources/{os.path.basename(fmu)}"
        with open(fmu, "rb") as f:
            resources[sources[name]] = f.read()
    own = {CHUTE: CHUTE_PARAMETERS if chute_parameters is None else chute_parameters,
           SEPARATOR: SEPARATOR_PARAMETERS if separator_parameters is None else separator_parameters}
    ssv = {}
    for name, variables in ((CHUTE, chute), (SEPARATOR, separator)):
        ssv[name] = f"resources/{name}.ssv"
        resources[ssv[name]] = _xml(parameter_values(shared | dict(own[name]), variables))
    ssd = system_structure(chute, separator, chute_source=sources[CHUTE],
                           separator_source=sources[SEPARATOR], chute_ssv=ssv[CHUTE],
                           separator_ssv=ssv[SEPARATOR], start_time=start_time,
                           stop_time=stop_time, step_size=step_size)
    if epoch is None:
        epoch = int(os.environ.get("SOURCE_DATE_EPOCH", "315532800"))
    date = time.gmtime(max(int(epoch), 315532800))[:6]
    os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
    tmp = f"{out}.tmp"
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        for path, data in [(SSD_NAME, _xml(ssd))] + sorted(resources.items()):
            info = zipfile.ZipInfo(path, date_time=date)
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, data)
    os.replace(tmp, out)
    return out
