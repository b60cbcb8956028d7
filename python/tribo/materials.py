"""The materials table (tribo/data/materials.toml, sources in docs/materials.md): a particle
and a wall by name, turned into the SI FMU's start values.

    import tribo
    tribo.materials.particles()                     # ['PE', 'PP', ..., 'glass']
    tribo.materials.walls()                         # ['PTFE', 'glass', 'steel', 'aluminium']
    tribo.materials.pair_sigma0("PE", "steel")      # -0.001 C/m^2 (sign: the particle's)
    start = tribo.materials.start_values("PE", "steel", semi_major_axis=0.5e-3,
                                         chute_length=0.3)

start_values gives a dict keyed by the SI FMU's parameter names (src/si/si_quantities.def):
the particle's and the wall's elastic constants, the particle's density, whether the wall
conducts (wall_conducting), the pair's sigma0 and the interface capacitance kappa, and every
override (any SI parameter by name, e.g. the
size, shape, chute and drop). Given sigma0 as an override, a pair without an entry is fine.

A materials file (`load(path)`, the `materials=` of the package's functions, `--materials
FILE` of the commands) has the table's schema and is read over it: its entries replace the
table's (a material's constants, a pair's sigma0, the interface) and add pairs, and its
[charging.<wall>.<particle>] tables give a pair's other charging parameters by the SI FMU's
names (charging_time, eta, backflow_time), which the pair's start values then carry.
`tribo calibrate` writes one (docs/calibration.md); [calibration...] tables hold where its
numbers came from and are not read as values. Every function here takes `materials` (None:
the package's table; a path; or a `Materials`).
"""

from __future__ import annotations

import copy
import hashlib
import math
import os
import tomllib
from dataclasses import dataclass, field
from functools import cache
from importlib import resources

from .fmu.instance import PARAMETER_CAUSALITIES, model_description
from .fmu.locate import find_fmu
from .input_files import read_input, shown



class MaterialError(ValueError):
    """An unknown material, a material in a role it has no entry for, a pair without sigma0,
    or an unknown SI parameter: the message is one line naming it and what exists."""


@dataclass(frozen=True)
class Material:
    key: str              # the name to look it up by, e.g. "PE"
    name: str             # what it is, e.g. "polyethylene (high density)"
    youngs_modulus: float  # Pa
    poisson_ratio: float
    density: float        # kg/m^3
    roles: tuple[str, ...]  # "particle", "wall"
    conducting: bool = False  # a wall: a grounded metal (the gas's limit's image form, section 8e)


# the sections of a materials file, and what each may hold
SECTIONS = ("material", "sigma0", "charging", "interface", "calibration")
MATERIAL_KEYS = ("name", "youngs_modulus", "poisson_ratio", "density", "roles", "conducting")
# a pair's charging parameters besides sigma0 (the SI FMU's names, docs/model.md sections 5, 8)
CHARGING_KEYS = ("charging_time", "eta", "backflow_time")
INTERFACE_KEYS = ("epsilon0", "gap")


@dataclass(frozen=True)
class Materials:
    """A materials table: the package's (data/materials.toml), or a materials file read
    over it (`load`). `source` says which; `sha256` is the file's (None for the
    package's)."""

    table: dict = field(hash=False, compare=False, repr=False)
    source: str = "the package's table"
    sha256: str | None = None

    def _materials(self) -> dict[str, Material]:
        return {key: Material(key, row["name"], float(row["youngs_modulus"]),
                              float(row["poisson_ratio"]), float(row["density"]),
                              tuple(row["roles"]), bool(row.get("conducting", False)))
                for key, row in self.table["material"].items()}

    def names(self, role: str) -> list[str]:
        return [k for k, m in self._materials().items() if role in m.roles]

    def material(self, name: str, role: str | None = None) -> Material:
        if role not in (None, "particle", "wall"):
            raise MaterialError(f"role {role!r}: not one of 'particle', 'wall'")
        known = self.names(role) if role else list(self.table["material"])
        for key in known:
            if key.lower() == str(name).lower():
                return self._materials()[key]
        what = f"{role} material" if role else "material"
        raise MaterialError(f"unknown {what} {name!r}; known: {', '.join(known)}")

    def sigma0_limit(self) -> float:
        return float(self.table["sigma0"]["limit"])

    def pairs(self) -> dict:
        """wall -> {particle: sigma0}."""
        return {k: v for k, v in self.table["sigma0"].items() if isinstance(v, dict)}

    def pair_sigma0(self, particle: str, wall: str) -> float:
        p = self.material(particle, "particle").key
        w = self.material(wall, "wall").key
        pairs = self.pairs()
        if p in pairs.get(w, {}):
            return float(pairs[w][p])
        listed = ", ".join(f"{pk}/{wk}" for wk, row in pairs.items() for pk in row)
        raise MaterialError(f"no sigma0 for particle {p} on wall {w} (give sigma0=...); "
                            f"pairs with one: {listed}")

    def pair_charging(self, particle: str, wall: str) -> dict[str, float]:
        """The pair's charging parameters besides sigma0 that the table gives (CHARGING_KEYS),
        by the SI FMU's names; {} where it gives none (the FMU's defaults hold)."""
        p = self.material(particle, "particle").key
        w = self.material(wall, "wall").key
        row = self.table.get("charging", {}).get(w, {}).get(p, {})
        return {k: float(row[k]) for k in CHARGING_KEYS if k in row}

    def interface_capacitance(self) -> float:
        row = self.table["interface"]
        return float(row["epsilon0"]) / float(row["gap"])

    def pair_values(self, particle: str, wall: str, sigma0: bool = True) -> dict[str, float]:
        p = self.material(particle, "particle")
        w = self.material(wall, "wall")
        values = {
            "youngs_modulus_particle": p.youngs_modulus,
            "poisson_ratio_particle": p.poisson_ratio,
            "density": p.density,
            "youngs_modulus_wall": w.youngs_modulus,
            "poisson_ratio_wall": w.poisson_ratio,
            # the gas's limit takes the image form on a metal wall (section 8e)
            "wall_conducting": int(w.conducting),
            "interface_capacitance": self.interface_capacitance(),
        }
        if sigma0:
            values["sigma0"] = self.pair_sigma0(p.key, w.key)
            # the pair's other charging parameters go with its sigma0 (a calibration's)
            values.update(self.pair_charging(p.key, w.key))
        return values


@cache
def _table() -> dict:
    text = resources.files("tribo").joinpath("data/materials.toml").read_text(encoding="utf-8")
    return tomllib.loads(text)


@cache
def builtin() -> Materials:
    """The package's table (data/materials.toml)."""
    return Materials(_table())


def load(path: str) -> Materials:
    """The materials file at `path` read over the package's table (see the module's
    text). MaterialError, one line naming the file and the entry, for a file that cannot be
    read, an unknown section or key, a material not in the package's table, a value that is
    not a finite number in its range, or a |sigma0| above the table's limit (1e-2 C/m2)."""
    data = read_input(path, MaterialError, "materials file")
    try:
        given = tomllib.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as e:
        raise MaterialError(f"materials file {path}: not TOML ({str(e).splitlines()[0]})") from None
    table = _merged(copy.deepcopy(_table()), given, path)
    _check_declared(table, given, path)
    return Materials(table, os.path.abspath(path), hashlib.sha256(data).hexdigest())


# a material's constants as the SI FMU's parameters of each role (its declared ranges)
ROLE_PARAMETERS = {"density": {"particle": "density"},
                   "youngs_modulus": {"particle": "youngs_modulus_particle",
                                      "wall": "youngs_modulus_wall"},
                   "poisson_ratio": {"particle": "poisson_ratio_particle",
                                     "wall": "poisson_ratio_wall"}}


def _check_declared(table: dict, given: dict, path: str) -> None:
    """The file's material constants within the SI FMU's declared ranges, refused naming the
    file and the entry (the FMU would refuse them later under its parameter's name alone);
    where the build has no SI FMU, its jobs cannot run and say so themselves."""
    try:
        variables = {v.name: v for v in model_description(find_fmu(None, variant="si")).modelVariables}
    except (OSError, ValueError):
        return
    for key, row in given.get("material", {}).items():
        for k, by_role in ROLE_PARAMETERS.items():
            for role in table["material"][key]["roles"]:
                v = variables.get(by_role.get(role, ""))
                if k not in row or v is None or v.min is None or v.max is None:
                    continue
                if not float(v.min) <= float(row[k]) <= float(v.max):
                    raise MaterialError(f"materials file {path}: [material.{key}] {k} = "
                                        f"{row[k]!r}: outside the range the model takes as a "
                                        f"{role}'s, [{float(v.min):g}, {float(v.max):g}] "
                                        f"({v.unit or v.declaredType and v.declaredType.unit or '1'})")


def table_of(materials=None) -> Materials:
    """The table `materials` names: None the package's, a path a materials file (`load`),
    a Materials itself."""
    if materials is None:
        return builtin()
    if isinstance(materials, Materials):
        return materials
    if isinstance(materials, (str, os.PathLike)):
        return load(os.fspath(materials))
    raise MaterialError(f"materials = {materials!r}: a materials file's path, or None for the "
                        f"package's table")


def _number(value, where: str, low: float = -math.inf, high: float = math.inf,
            open_low: bool = False) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) \
            or value < low or (open_low and value == low) or value > high:
        bound = f"{'(' if open_low else '['}{low:g}, {high:g}]"
        raise MaterialError(f"{where} = {value!r}: a finite number in {bound}")
    return float(value)


def _merged(table: dict, given: dict, path: str) -> dict:
    """The package's table with the file's entries over it, each checked."""
    unknown = [k for k in given if k not in SECTIONS]
    if unknown:
        raise MaterialError(f"materials file {path}: unknown section [{shown(unknown[0])}] (the "
                            f"sections are {', '.join(SECTIONS)})")
    for key, row in given.get("material", {}).items():
        where = f"materials file {path}: [material.{shown(key)}]"
        if key not in table["material"]:
            raise MaterialError(f"{where}: not a material of the package's table (known: "
                                f"{', '.join(table['material'])}); a file gives new values to "
                                f"the table's materials")
        if not isinstance(row, dict):
            raise MaterialError(f"{where}: a table of {', '.join(MATERIAL_KEYS)}")
        bad = [k for k in row if k not in MATERIAL_KEYS]
        if bad:
            raise MaterialError(f"{where}: unknown key {shown(bad[0])} (known: {', '.join(MATERIAL_KEYS)})")
        for k, limits in (("youngs_modulus", (0, math.inf, True)), ("poisson_ratio", (0, 0.5, False)),
                          ("density", (0, math.inf, True))):
            if k in row:
                _number(row[k], f"{where} {k}", limits[0], limits[1], open_low=limits[2])
        if "roles" in row and (not isinstance(row["roles"], list)
                               or not set(row["roles"]) <= {"particle", "wall"} or not row["roles"]):
            raise MaterialError(f"{where} roles = {row['roles']!r}: a list of 'particle', 'wall'")
        if "conducting" in row and not isinstance(row["conducting"], bool):
            raise MaterialError(f"{where} conducting = {row['conducting']!r}: true (a grounded "
                                f"metal wall) or false (an insulating one)")
        table["material"][key].update(row)
    sigma0 = given.get("sigma0", {})
    if "breakdown_limit" in sigma0:
        raise MaterialError(f"materials file {path}: [sigma0] breakdown_limit is not read: sigma0 "
                            f"is the contact's own density, within +-{table['sigma0']['limit']:g} "
                            f"C/m2, and the gas's limit is the SI parameter breakdown_model "
                            f"(docs/model.md section 8e)")
    if "limit" in sigma0:
        raise MaterialError(f"materials file {path}: [sigma0] limit is the table's bound on "
                            f"|sigma0| ({table['sigma0']['limit']:g} C/m2, the SI FMU's range); "
                            f"a file does not set it")
    limit = float(table["sigma0"]["limit"])
    for wall, row in sigma0.items():
        _pair_table(table, wall, row, path, "sigma0")
        for particle, value in row.items():
            _pair_names(table, particle, wall, path, "sigma0")
            _number(value, f"materials file {path}: [sigma0.{wall}] {particle}", -limit, limit)
            table["sigma0"].setdefault(wall, {})[particle] = float(value)
    for wall, row in given.get("charging", {}).items():
        _pair_table(table, wall, row, path, "charging")
        for particle, values in row.items():
            _pair_names(table, particle, wall, path, "charging")
            where = f"materials file {path}: [charging.{wall}.{particle}]"
            if not isinstance(values, dict):
                raise MaterialError(f"{where}: a table of {', '.join(CHARGING_KEYS)}")
            bad = [k for k in values if k not in CHARGING_KEYS]
            if bad:
                raise MaterialError(f"{where}: unknown key {shown(bad[0])} (known: {', '.join(CHARGING_KEYS)})")
            for k, v in values.items():
                _number(v, f"{where} {k}", 0)
            table.setdefault("charging", {}).setdefault(wall, {})[particle] = dict(values)
    interface = given.get("interface", {})
    bad = [k for k in interface if k not in INTERFACE_KEYS]
    if bad:
        raise MaterialError(f"materials file {path}: [interface] unknown key {shown(bad[0])} (known: "
                            f"{', '.join(INTERFACE_KEYS)})")
    for k, v in interface.items():
        table["interface"][k] = _number(v, f"materials file {path}: [interface] {k}", 0, open_low=True)
    if "calibration" in given:
        table["calibration"] = given["calibration"]
    return table


def _pair_table(table: dict, wall: str, row, path: str, section: str) -> None:
    if not isinstance(row, dict):
        raise MaterialError(f"materials file {path}: [{section}.{wall}]: a table by particle")
    m = table["material"].get(wall)
    if m is None or "wall" not in m["roles"]:
        walls = [k for k, v in table["material"].items() if "wall" in v["roles"]]
        raise MaterialError(f"materials file {path}: [{section}.{shown(wall)}]: unknown wall "
                            f"material; known: {', '.join(walls)}")


def _pair_names(table: dict, particle: str, wall: str, path: str, section: str) -> None:
    m = table["material"].get(particle)
    if m is None or "particle" not in m["roles"]:
        known = [k for k, v in table["material"].items() if "particle" in v["roles"]]
        raise MaterialError(f"materials file {path}: [{section}.{wall}] {shown(particle)}: "
                            f"unknown particle material; known: {', '.join(known)}")


def particles(materials=None) -> list[str]:
    """The materials a particle can be made of."""
    return table_of(materials).names("particle")


def walls(materials=None) -> list[str]:
    """The materials a chute can be made of."""
    return table_of(materials).names("wall")


def material(name: str, role: str | None = None, materials=None) -> Material:
    """A material by name (case-insensitive); with role ("particle" or "wall"), one that
    has an entry for it."""
    return table_of(materials).material(name, role)


def sigma0_limit(materials=None) -> float:
    """The bound on |sigma0|, C/m^2 (the SI FMU's declared range): sigma0 is the contact's
    own density, before the gas relaxes it (docs/model.md section 8e)."""
    return table_of(materials).sigma0_limit()


def pair_sigma0(particle: str, wall: str, materials=None) -> float:
    """The static saturation charge density of the particle on the wall, C/m^2; its sign is
    the polarity of the particle's charge."""
    return table_of(materials).pair_sigma0(particle, wall)


def interface_capacitance(materials=None) -> float:
    """kappa = epsilon0 / z0, F/m^2: the condenser model's capacitance per unit area of
    surfaces in contact across the gap z0 (docs/materials.md)."""
    return table_of(materials).interface_capacitance()


def with_pair(particle: str, wall: str, settings: dict, materials=None) -> dict:
    """`settings` (SI parameters by name) with the pair's values from a materials file
    under them: what the jobs that look their materials up in the package's table take,
    so that a materials file drives them; the settings unchanged without one."""
    if materials is None:
        return dict(settings)
    return dict(table_of(materials).pair_values(particle, wall, sigma0="sigma0" not in settings),
                **settings)


def si_parameters(fmu: str | int | None = None) -> tuple[str, ...]:
    """The SI FMU's parameter names, in the order of its description (`fmu`: a path, or 2 /
    3 for the build's SI FMU, default 3)."""
    md = model_description(find_fmu(fmu, variant="si"))
    return tuple(v.name for v in md.modelVariables if v.causality in PARAMETER_CAUSALITIES)


def start_values(particle: str, wall: str, fmu: str | int | None = None, materials=None,
                 **overrides) -> dict[str, float]:
    """The SI FMU's start values of a particle on a wall, for any importer: E, Poisson's
    ratio and density of the particle, E and Poisson's ratio of the wall, the pair's sigma0
    (and its other charging parameters where a materials file gives them), kappa; then the
    overrides, which win. The FMU's own names and units (SI, angles in
    radians: `tilt`, `phi0`; the size as `semi_major_axis` a), since these go to the FMU
    as they are; the package's functions take angles in degrees and the size as `size`.
    The overrides' names are checked against the SI FMU they are for (`fmu`: a path, or 2 /
    3 for the build's, default 3)."""
    known = si_parameters(fmu)
    unknown = [k for k in overrides if k not in known]
    if unknown:
        raise MaterialError(f"unknown SI parameter {unknown[0]!r}; known: {', '.join(known)}")
    values = pair_values(particle, wall, sigma0="sigma0" not in overrides, materials=materials)
    values.update(overrides)
    return values


def pair_values(particle: str, wall: str, sigma0: bool = True, materials=None) -> dict[str, float]:
    """The SI FMU's values that the pair sets: E, Poisson's ratio and density of the
    particle, E and Poisson's ratio of the wall, kappa and (if `sigma0`) the pair's sigma0
    with its other charging parameters where the table gives them (a materials file's
    [charging] table)."""
    return table_of(materials).pair_values(particle, wall, sigma0)
