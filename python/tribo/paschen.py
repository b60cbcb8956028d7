"""The gas's limit on a charged region's density, sigma_P(L) (docs/model.md section 8e), as
the package states it beside the core: the ceilings of repeated impacts and of a grain
(its limit sigma_P(R_s) A_s), the validation's expected figures, and an independent check
of the core's table (its own minimisation over the gap, here by a dense grid refined by
golden sections, not the core's method).

    import tribo
    tribo.paschen.limit(10e-6)                 # 6.7e-4 C/m2: a 10 um region in air, metal wall
    tribo.paschen.limit(1e-3, conducting=False)
    tribo.paschen.grain_limit(2e-3, 1.0)       # C: the 2 mm sphere's, sigma_P(R_s) A_s

A disc of radius L charged to sigma at the gap z from the wall stands the voltage
V(z) = (sigma / eps0) g(z) across the gap, g(z) = h + z - sqrt(z^2 + h^2), h = L/2 for a
grounded metal wall (its image), h = L for an insulating one (the pair of discs +-sigma);
the gas breaks down where V(z) reaches Paschen's Vb(z) = B p z / (ln(A p z) - ln(ln(1 +
1/gamma))), held at its minimum's voltage for gaps shorter than the minimum's. sigma_P(L)
= eps0 min over z of Vb(z) / g(z). Air's constants (the SI FMU's defaults): p = 101325 Pa,
A = 11.25 /(Pa m), B = 273.8 V/(Pa m), gamma = 0.01.
"""

import math
from dataclasses import dataclass

EPSILON0 = 8.8541878128e-12  # F/m
# the SI FMU's parameters that set the gas, with air's values (docs/model.md section 8e)
GAS_PARAMETERS = {"gas_pressure": 101325.0, "paschen_A": 11.25, "paschen_B": 273.8,
                  "secondary_emission": 0.01}
GRID_PER_DECADE = 200  # the gap's grid before the golden sections (refined to 1e-10 in log z)


@dataclass(frozen=True)
class Gas:
    """A gas by Paschen's constants: pressure p (Pa), A (1/(Pa m)), B (V/(Pa m)), the
    secondary emission gamma (0 < gamma < 1)."""

    pressure: float = GAS_PARAMETERS["gas_pressure"]
    A: float = GAS_PARAMETERS["paschen_A"]
    B: float = GAS_PARAMETERS["paschen_B"]
    gamma: float = GAS_PARAMETERS["secondary_emission"]

    def __post_init__(self):
        for name, value, ok in (("gas_pressure", self.pressure, self.pressure > 0),
                                ("paschen_A", self.A, self.A > 0),
                                ("paschen_B", self.B, self.B > 0),
                                ("secondary_emission", self.gamma, 0 < self.gamma < 1)):
            if not (isinstance(value, (int, float)) and math.isfinite(value) and ok):
                rng = "(0, 1)" if name == "secondary_emission" else "(0, inf)"
                raise ValueError(f"{name} = {value!r}: a finite number in {rng}")

    @classmethod
    def of(cls, settings: dict | None = None, md=None) -> "Gas":
        """The gas of SI settings (by the FMU's names), the rest the FMU's start values
        (`md`, its model description) or air's."""
        from .fmu.names import start_value  # only where a description is given
        values = {}
        for name, default in GAS_PARAMETERS.items():
            value = (settings or {}).get(name)
            if value is None and md is not None:
                value = start_value(md, name)
            values[name] = float(default if value is None else value)
        return cls(values["gas_pressure"], values["paschen_A"], values["paschen_B"],
                   values["secondary_emission"])

    @property
    def log_ln(self) -> float:
        return math.log(math.log(1.0 + 1.0 / self.gamma))

    @property
    def minimum_gap(self) -> float:
        """The gap of the Paschen minimum, m: A p d = e ln(1 + 1/gamma)."""
        return math.exp(1.0 + self.log_ln) / (self.A * self.pressure)

    @property
    def minimum_voltage(self) -> float:
        """The Paschen minimum's voltage, V: (B / A) e ln(1 + 1/gamma)."""
        return self.B / self.A * math.exp(1.0 + self.log_ln)

    def breakdown_voltage(self, gap: float) -> float:
        """Vb(gap), V; the minimum's voltage below the minimum's gap (section 8e's choice)."""
        if gap <= self.minimum_gap:
            return self.minimum_voltage
        pd = self.pressure * gap
        return self.B * pd / (math.log(self.A * pd) - self.log_ln)


AIR = Gas()


def _ratio(gas: Gas, h: float, z: float) -> float:
    """Vb(z) / g(z) for the half-width h (section 8e)."""
    # g = h + z - sqrt(z^2 + h^2), written without the cancellation for z >> h
    g = h - h * h / (z + math.sqrt(z * z + h * h))
    return gas.breakdown_voltage(z) / g


def limit(radius: float, gas: Gas = AIR, conducting: bool = True) -> float:
    """sigma_P(L), C/m2, of a region of radius L (m) separating from a metal wall
    (`conducting`, the image form) or an insulating one (the pair form)."""
    if not (isinstance(radius, (int, float)) and math.isfinite(radius) and radius > 0):
        raise ValueError(f"radius = {radius!r}: a region's radius in m, a positive number")
    h = radius / 2.0 if conducting else radius
    # the ratio falls as 1/z below the minimum's gap (Vb held, g ~ z): its minimum lies at
    # or above that gap, and below a gap where g has saturated and Vb grows (100 h)
    low = math.log10(gas.minimum_gap)
    high = max(low, math.log10(100.0 * h)) + 1.0
    n = max(8, int(GRID_PER_DECADE * (high - low)))
    zs = [10 ** (low + (high - low) * k / n) for k in range(n + 1)]
    values = [_ratio(gas, h, z) for z in zs]
    k = min(range(len(values)), key=values.__getitem__)
    a, b = math.log10(zs[max(k - 1, 0)]), math.log10(zs[min(k + 1, n)])
    golden = (math.sqrt(5.0) - 1.0) / 2.0
    while b - a > 1e-10:
        c, d = b - golden * (b - a), a + golden * (b - a)
        if _ratio(gas, h, 10 ** c) <= _ratio(gas, h, 10 ** d):
            b = d
        else:
            a = c
    return EPSILON0 * min(values[k], _ratio(gas, h, 10 ** (0.5 * (a + b))))


def spheroid_area(size: float, epsilon: float) -> float:
    """The surface area (m2) of the prolate spheroid of long diameter `size` (2a) and
    roundness epsilon (semi-axes a, b, b; b = epsilon a): 2 pi b^2 + 2 pi a b asin(e)/e,
    e = sqrt(1 - epsilon^2); 4 pi a^2 for a sphere (docs/model.md section 8c)."""
    a = size / 2.0
    b = epsilon * a
    e = math.sqrt(max(0.0, 1.0 - epsilon * epsilon))
    ratio = math.asin(e) / e if e > 1e-8 else 1.0 + e * e / 6.0  # asin(e)/e -> 1 + e^2/6
    return 2.0 * math.pi * b * b + 2.0 * math.pi * a * b * ratio


def grain_limit(size: float, epsilon: float, gas: Gas = AIR, conducting: bool = True) -> float:
    """The grain's limit sigma_P(R_s) A_s, C (section 8e): R_s the radius of the sphere of
    the spheroid's area A_s."""
    area = spheroid_area(size, epsilon)
    return limit(math.sqrt(area / (4.0 * math.pi)), gas, conducting) * area
