"""What the fuzz model needs to know of an FMU's front end (fmu/front_end.h): whether its
parameters make a model, whether the running model takes an input or a tunable value, the
unit of the FMU's time in the model's, whether the core resolves a time, and the set-ups
worth running and mutating.

The dimensionless FMUs pass everything on as it is. The SI FMUs map a physical set-up onto
the model by docs/model.md section 8: which model parameter each SI parameter sets, and how,
is read from the SI table's TRIBO_MAPS rows (src/si/si_quantities.def, the rows si.c's mapping
is generated from); the units of each conversion are written here again from section 8 (not
from src/si/si.c), and the model's ranges are read from the dimensionless FMU's reviewed
description (modelDescription/fmi3.xml), so that the fuzz suite checks the SI FMU's refusals
against an independent statement of the arithmetic.

The separator's FMUs pass everything on to their own core (docs/model.md section 10), whose
combinations are written here again from docs/separator.md."""

import math
import os
import re
import xml.etree.ElementTree as ET

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MODEL_DESCRIPTION = os.path.join(ROOT, "modelDescription", "fmi3.xml")
SI_TABLE = os.path.join(ROOT, "src", "si", "si_quantities.def")
REGISTRY = os.path.join(ROOT, "src", "chute", "charge", "charge_registry.def")


def charge_models():
    """The registered charge models' names by slot (src/chute/charge/charge_registry.def)."""
    with open(REGISTRY, encoding="utf-8") as f:
        rows = re.findall(r"^TRIBO_CHARGE_MODEL\(\w+, (\w+), (\d+),", f.read(), re.MULTILINE)
    return [name for name, _ in sorted(rows, key=lambda row: int(row[1]))]


CHARGE_MODELS = charge_models()


def si_mapping():
    """The SI table's TRIBO_MAPS rows: SI name -> (model name, conversion)."""
    with open(SI_TABLE, encoding="utf-8") as f:
        rows = re.findall(r"^TRIBO_MAPS\((\w+), (\w+), (\w+)\)", f.read(), re.MULTILINE)
    return {si: (model, how.lower()) for si, model, how in rows}


GRID_MAX_STEPS = 2.0**45  # the fixed step's grid (src/chute/integrators/integrator_fixed_step.c)


def rigid_stick_valid(values):
    return values["stick_model"] == 0 or (values["integrator"] != 0 and
                                           values["damping_point"] == 0)


class Chute:
    """What the chute's FMUs share: the fixed step's grid, the chute's end."""

    def resolves(self, core_end, values):
        """Whether the core can advance to its time core_end (the fixed step: a grid of dt
        resolved below 2^45 steps)."""
        return values["integrator"] != 0 or core_end / values["dt"] < GRID_MAX_STEPS

    def chute_length(self, values):
        return values["chute_length"]

    # runs that end where the particle leaves the chute, now and then (set with probability)
    ending = (0.2, "chute_length", [0.05, 2.0])

    @staticmethod
    def base_scenes():
        """Set-ups worth mutating the states of: each integrator, the rigid stick, rolling
        resistance (a grain that turns, and one that comes to rest and ends its run there,
        docs/model.md section 3c), a discarded step, the lifecycle states before Step Mode, a
        run past the chute's end."""
        compliant = {"integrator": 0, "stick_model": 0}  # the fixed step has no rigid stick
        return [compliant, {"integrator": 1}, {"integrator": 2},
                {"integrator": 1, "stick_model": 1, "mu": 1.0, "epsilon": 0.5},
                {"integrator": 1, "stick_model": 1, "mu": 0.5, "epsilon": 1.0, "mu_roll": 0.2},
                {"integrator": 1, "stick_model": 1, "mu": 1.5, "epsilon": 0.5, "mu_roll": 1.0},
                {**compliant, "mu_roll": 0.3},
                {"integrator": 1, "mu": 1.0, "nu": 1.0},
                {**compliant, "work_limit": 50, "discard": True},
                {"lifecycle": "Initialization Mode"}, {"lifecycle": "Instantiated"}, {"integrator": 1, "chute_length": 0.01},
                {**compliant, "chute_length": 0.01}]


class Dimensionless(Chute):
    """The model's own variables."""

    # the work limit's bound at the declared extremes that cost the most per unit of work
    # (docs/work_limit.md), and the breakdown limit on 1e5 segments
    work_bound_scenes = [
        {"n_segments": 100000, "Sigma_bd": 5e-324}, {"n_segments": 100000, "Sigma_bd": 1e-6},
        {"n_segments": 100000, "integrator": 2, "Sigma_bd": 5e-324},
        {"n_segments": 100000, "integrator": 0, "Sigma_bd": 5e-324},
        {"epsilon": 1e-3}, {"epsilon": 1.0, "stick_model": 1}, {"Gamma": 10.0},
        {"Gamma": 1e-12}, {"mu": 100.0, "nu": 100.0}, {"rtol": 1e-14, "atol": 1e-20},
        {"integrator": 0, "dt": 1e-9, "Gamma": 10.0}, {"Omega0": 100.0, "epsilon": 1e-3},
        # the spheroid's bands under a contact as wide as the weight can press it
        {"n_segments": 100000, "grain_geometry": 1, "Gamma": 10.0},
        {"n_segments": 100000, "grain_geometry": 1, "Gamma": 10.0, "tau0": 0.0}]
    # each in one doStep of this many of the model's units of time (the fixed step resolves
    # it at dt = 1e-9)
    work_bound_step = 1e4

    def scene_valid(self, values):
        """The core's combinations: the drop lies on the chute, and the rigid stick
        (docs/model.md section 3b) needs the event-driven integrator and the dashpot at
        the centre."""
        return values["X0"] < values["chute_length"] and rigid_stick_valid(values)

    def inputs_valid(self, values):
        return True

    def time_unit(self, values):
        return 1.0

    def accepts_while_running(self, name, value, values):
        return True


def model_ranges():
    """The model's parameters and inputs: name -> (min, max, max given)."""
    root = ET.parse(MODEL_DESCRIPTION).getroot()
    out = {}
    for element in root.find("ModelVariables"):
        a = element.attrib
        if a.get("causality") in ("parameter", "structuralParameter", "input"):
            out[a["name"]] = (float(a.get("min", -math.inf)), float(a.get("max", math.inf)),
                              "max" in a)
    return out


class SI(Chute):
    """docs/model.md section 8."""

    # on an unbounded chute: on the default one (0.3 m) the grain leaves long before a
    # doStep reaches the limit
    work_bound_scenes = [dict(scene, chute_length=math.inf) for scene in [
        {"epsilon": 1.0}, {"epsilon": 0.001}, {"gravity": 1e4},
        {"youngs_modulus_particle": 1e3, "youngs_modulus_wall": 1e3},
        {"n_segments": 100000, "breakdown_density": 5e-324}, {"n_segments": 100000, "epsilon": 1.0},
        {"n_segments": 100000, "gravity": 1e4}, {"epsilon": 1.0, "charging_time": 1e-3},
        {"integrator": 2, "epsilon": 1.0}, {"rtol": 1e-14, "atol": 1e-20}]]
    work_bound_step = 1e6  # about a second: the drop and the contact after it

    def __init__(self):
        self.ranges = model_ranges()
        mapping = si_mapping()
        # SI parameter -> (model parameter, conversion); the inputs: SI name -> model name
        self.MAP = {si: m for si, m in mapping.items() if m[1] != "force"}
        self.INPUTS = {si: model for si, (model, how) in mapping.items() if how == "force"}

    @staticmethod
    def carried_model_included(values):
        """The charge model `charge_to_mass` carries (charge_to_mass_model, the registry's
        row order from 1; 0, the first included) runs (its switch is on), or no model runs."""
        def included(slot):
            return values[f"charge_model_{CHARGE_MODELS[slot]}"] != 0

        named = int(values["charge_to_mass_model"])
        return named == 0 or not any(included(k) for k in range(len(CHARGE_MODELS))) \
            or included(named - 1)

    @staticmethod
    def units(v):
        """The set-up's units (model.md section 8), each computed as the SI FMU does."""
        a = v["semi_major_axis"]
        if v["stiffness_source"] == 0:
            k = v["contact_stiffness"]
        else:
            nu_p, nu_w = v["poisson_ratio_particle"], v["poisson_ratio_wall"]
            e_star = 1.0 / ((1.0 - nu_p * nu_p) / v["youngs_modulus_particle"] +
                            (1.0 - nu_w * nu_w) / v["youngs_modulus_wall"])
            k = (math.pi / 4.0) * e_star
        m = v["density"] * math.pi * a * a * v["epsilon"]
        t_star = math.sqrt(m / k)
        return {"a": a, "t_star": t_star, "velocity": a / t_star, "force": k * a,
                "sigma": math.sqrt(v["interface_capacitance"] * k * a), "mass": m,
                "polarity": -1.0 if v["sigma0"] < 0.0 else 1.0}

    @staticmethod
    def convert(u, how, x):
        return {"same": lambda: x, "length": lambda: x / u["a"], "time": lambda: x / u["t_star"],
                "speed": lambda: x / u["velocity"], "rate": lambda: x * u["t_star"],
                "density": lambda: abs(x) / u["sigma"], "force": lambda: x / u["force"],
                # a density in the pair's polarity (section 8c): positive where it is the pair's
                "polarised": lambda: u["polarity"] * x / u["sigma"],
                # section 8b: a limit of 0 is none; one too small for a double in the
                # model's units is the smallest double
                "limit": lambda: max(x / u["sigma"], 5e-324) if x > 0.0 else math.inf}[how]()

    def in_range(self, model_name, x):
        lo, hi, bounded = self.ranges[model_name]
        if x == math.inf and not bounded:
            return True
        return math.isfinite(x) and lo <= x <= hi

    def scene_valid(self, values):
        if not (values["x0"] < values["chute_length"] and rigid_stick_valid(values)):
            return False
        if not self.carried_model_included(values):
            return False
        u = self.units(values)
        for si, (model, how) in self.MAP.items():
            if how == "density" and values[si] == 0.0:
                continue  # a neutral pair: the model's default, every charge output times 0
            if not self.in_range(model, self.convert(u, how, values[si])):
                return False
        return self.in_range("Gamma", u["mass"] * values["gravity"] / u["force"])

    def inputs_valid(self, values):
        u = self.units(values)
        return all(self.in_range(model, values[si] / u["force"]) for si, model in self.INPUTS.items())

    def time_unit(self, values):
        return self.units(values)["t_star"]

    def accepts_while_running(self, name, value, values):
        u = self.units(values)
        if name in self.INPUTS:
            return self.in_range(self.INPUTS[name], value / u["force"])
        model, how = self.MAP[name]
        if how == "density" and value == 0.0:
            return True
        return self.in_range(model, self.convert(u, how, value))


class Separator:
    """docs/model.md section 10: the grain fits the gap and enters between the plates."""

    # (its work limit counts CVODE steps; the grain released at the start)
    work_bound_scenes = [
        {"released": 1, "rtol": 1e-12, "atol": 1e-20}, {"released": 1, "air_viscosity": 5e-324},
        {"released": 1, "height": 100.0, "gravity": 1e-6, "rtol": 1e-12},
        {"released": 1, "semi_major_axis": 1e-7, "air_viscosity": 1.0, "height": 100.0}]
    work_bound_step = 1e3

    def scene_valid(self, values):
        x_limit = values["gap"] / 2 - values["semi_major_axis"]
        return x_limit > 0 and abs(values["x_entry"]) < x_limit

    def inputs_valid(self, values):
        return True

    def time_unit(self, values):
        return 1.0

    def accepts_while_running(self, name, value, values):
        return True

    def resolves(self, core_end, values):
        return True

    def chute_length(self, values):
        return math.inf

    # runs that end at the bins or on a plate: the grain released at the first step
    ending = (0.5, "released", [1])

    @staticmethod
    def base_scenes():
        """Set-ups worth mutating the states of: held at the entry, in flight (with drag, in
        vacuum), landed, caught, a discarded step, the lifecycle states before Step Mode."""
        flying = {"released": 1, "u_entry": 0.4, "v_entry": -0.1, "charge_to_mass": 2e-6}
        return [{}, flying, {**flying, "air_density": 0.0, "air_viscosity": 0.0},
                {**flying, "height": 1e-3}, {**flying, "charge_to_mass": 1.0},
                {**flying, "work_limit": 1, "discard": True},
                {"lifecycle": "Initialization Mode"}, {"lifecycle": "Instantiated"}]


def front_end_of(model_identifier):
    if model_identifier.startswith("tribo_si_"):
        return SI()
    if model_identifier.startswith("tribo_separator_"):
        return Separator()
    return Dimensionless()
