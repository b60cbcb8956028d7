"""The materials table (tribo/data/materials.toml, sources in docs/materials.md): a particle
and a wall by name, turned into the SI FMU's start values.

    import tribo
    tribo.materials.particles()                     # ['PE', 'PP', ..., 'glass']
    tribo.materials.walls()                         # ['PTFE', 'glass', 'steel', 'aluminium']
    tribo.materials.pair_sigma0("PE", "steel")      # -1e-05 C/m^2 (sign: the particle's)
    start = tribo.materials.start_values("PE", "steel", semi_major_axis=0.5e-3,
                                         chute_length=0.3)

start_values gives a dict keyed by the SI FMU's parameter names (src/si/si_quantities.def):
the particle's and the wall's elastic constants, the particle's density, the pair's sigma0
and the interface capacitance kappa, and every override (any SI parameter by name, e.g. the
size, shape, chute and drop). Given sigma0 as an override, a pair without an entry is fine.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from functools import cache
from importlib import resources

from .fmu.instance import PARAMETER_CAUSALITIES, model_description
from .fmu.locate import find_fmu



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


@cache
def _table() -> dict:
    text = resources.files("tribo").joinpath("data/materials.toml").read_text(encoding="utf-8")
    return tomllib.loads(text)


@cache
def _materials() -> dict[str, Material]:
    out = {}
    for key, row in _table()["material"].items():
        out[key] = Material(key, row["name"], float(row["youngs_modulus"]),
                            float(row["poisson_ratio"]), float(row["density"]),
                            tuple(row["roles"]))
    return out


def _names(role: str) -> list[str]:
    return [k for k, m in _materials().items() if role in m.roles]


def particles() -> list[str]:
    """The materials a particle can be made of."""
    return _names("particle")


def walls() -> list[str]:
    """The materials a chute can be made of."""
    return _names("wall")


def material(name: str, role: str | None = None) -> Material:
    """A material by name (case-insensitive); with role ("particle" or "wall"), one that
    has an entry for it."""
    if role not in (None, "particle", "wall"):
        raise MaterialError(f"role {role!r}: not one of 'particle', 'wall'")
    known = _names(role) if role else list(_materials())
    for key in known:
        if key.lower() == str(name).lower():
            return _materials()[key]
    what = f"{role} material" if role else "material"
    raise MaterialError(f"unknown {what} {name!r}; known: {', '.join(known)}")


def breakdown_limit() -> float:
    """The air-breakdown limit of a surface charge density, C/m^2 (the bound on |sigma0|)."""
    return float(_table()["sigma0"]["breakdown_limit"])


def pair_sigma0(particle: str, wall: str) -> float:
    """The static saturation charge density of the particle on the wall, C/m^2; its sign is
    the polarity of the particle's charge."""
    p = material(particle, "particle").key
    w = material(wall, "wall").key
    pairs = {k: v for k, v in _table()["sigma0"].items() if isinstance(v, dict)}
    if p in pairs.get(w, {}):
        return float(pairs[w][p])
    listed = ", ".join(f"{pk}/{wk}" for wk, row in pairs.items() for pk in row)
    raise MaterialError(f"no sigma0 for particle {p} on wall {w} (give sigma0=...); "
                        f"pairs with one: {listed}")


def interface_capacitance() -> float:
    """kappa = epsilon0 / z0, F/m^2: the condenser model's capacitance per unit area of
    surfaces in contact across the gap z0 (docs/materials.md)."""
    row = _table()["interface"]
    return float(row["epsilon0"]) / float(row["gap"])


def si_parameters(fmu: str | int | None = None) -> tuple[str, ...]:
    """The SI FMU's parameter names, in the order of its description (`fmu`: a path, or 2 /
    3 for the build's SI FMU, default 3)."""
    md = model_description(find_fmu(fmu, variant="si"))
    return tuple(v.name for v in md.modelVariables if v.causality in PARAMETER_CAUSALITIES)


def start_values(particle: str, wall: str, fmu: str | int | None = None,
                 **overrides) -> dict[str, float]:
    """The SI FMU's start values of a particle on a wall, for any importer: E, Poisson's
    ratio and density of the particle, E and Poisson's ratio of the wall, the pair's sigma0,
    kappa; then the overrides, which win. The FMU's own names and units (SI, angles in
    radians: `tilt`, `phi0`; the size as `semi_major_axis` a), since these go to the FMU
    as they are; the package's functions take angles in degrees and the size as `size`.
    The overrides' names are checked against the SI FMU they are for (`fmu`: a path, or 2 /
    3 for the build's, default 3)."""
    known = si_parameters(fmu)
    unknown = [k for k in overrides if k not in known]
    if unknown:
        raise MaterialError(f"unknown SI parameter {unknown[0]!r}; known: {', '.join(known)}")
    values = pair_values(particle, wall, sigma0="sigma0" not in overrides)
    values.update(overrides)
    return values


def pair_values(particle: str, wall: str, sigma0: bool = True) -> dict[str, float]:
    """The SI FMU's values that the pair sets: E, Poisson's ratio and density of the
    particle, E and Poisson's ratio of the wall, kappa and (if `sigma0`) the pair's sigma0."""
    p = material(particle, "particle")
    w = material(wall, "wall")
    values = {
        "youngs_modulus_particle": p.youngs_modulus,
        "poisson_ratio_particle": p.poisson_ratio,
        "density": p.density,
        "youngs_modulus_wall": w.youngs_modulus,
        "poisson_ratio_wall": w.poisson_ratio,
        "interface_capacitance": interface_capacitance(),
    }
    if sigma0:
        values["sigma0"] = pair_sigma0(p.key, w.key)
    return values
