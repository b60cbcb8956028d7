"""The SI FMUs (tribo_si_fmi2, tribo_si_fmi3: src/si/si_quantities.def, docs/model.md §8).

Their units parse in Pint (from the BaseUnit exponents and factor, and by name) and agree,
their display units convert as Pint converts, and §8's relations hold between the declared
units and between the calculated parameters' values. The SI FMU and the dimensionless FMU
given the numbers the SI FMU derived give the same run. The reference case leaves its
chute in fmpy's simulate_fmu. Bad SI input, and SI input whose derived numbers fall outside
the model's ranges, are refused through the logger naming the SI variables."""

import math
import re

import numpy as np
import pint
import pytest
from fmpy import read_model_description, simulate_fmu

from tribo_fmu import ERROR, OK, VERSIONS, WARNING, Slave, libcosim_run, status_of

U = pint.UnitRegistry()
SI = "tribo_si"
BASE_UNITS = {"kg": U.kilogram, "m": U.metre, "s": U.second, "A": U.ampere, "K": U.kelvin,
              "mol": U.mole, "cd": U.candela, "rad": U.radian}


def pint_unit(name):
    """A unit name as Pint reads it: FMI names write exponents as trailing digits (m2), Pint
    as m**2."""
    return U(re.sub(r"([A-Za-z])(\d+)", r"\1**\2", name))


def from_base_unit(base):
    q = base.factor * U.dimensionless
    for attribute, unit in BASE_UNITS.items():
        q = q * unit ** getattr(base, attribute)
    return q


def same_unit(a, b):
    """Whether two Pint quantities are the same unit: the same dimensions, factor 1."""
    ratio = (a / b).to_base_units()
    return ratio.dimensionless and ratio.magnitude == pytest.approx(1.0, rel=1e-15)


@pytest.fixture(scope="module", params=VERSIONS)
def described(request, fmu_file):
    return read_model_description(fmu_file(request.param, SI), validate=True)


# ---- units ---------------------------------------------------------------------------------


def test_every_unit_parses_in_pint_by_its_base_units_and_by_its_name(described):
    assert len(described.unitDefinitions) >= 19
    for unit in described.unitDefinitions:
        assert unit.baseUnit is not None, unit.name
        assert unit.baseUnit.offset == 0, unit.name
        assert same_unit(from_base_unit(unit.baseUnit), pint_unit(unit.name)), unit.name


def test_every_display_unit_is_pints_conversion(described):
    shown = {}
    for unit in described.unitDefinitions:
        for display in unit.displayUnits:
            shown[display.name] = unit.name
            converted = (1 * pint_unit(unit.name)).to(pint_unit(display.name)).magnitude
            assert display.factor == pytest.approx(converted, rel=1e-14), (unit.name, display.name)
            assert display.offset == 0
    # the display units an engineer reads a grain's size, charge and q/m in
    assert {"deg", "mm", "µm", "ms", "GPa", "nC", "pC", "µC/kg", "nC/kg"} <= set(shown)


def test_every_real_has_its_units_quantity(fmu_dir):
    """`quantity` on every real variable whose unit has one (the TRIBO_UNIT row's), and the
    variables of one unit share it."""
    import xml.etree.ElementTree as ET

    for version in VERSIONS:
        root = ET.parse(f"{fmu_dir(version, SI)}/modelDescription.xml").getroot()
        quantity_of = {}
        for element in root.find("ModelVariables"):
            a = element[0].attrib if version == 2 else element.attrib
            if "unit" not in a:
                continue
            if a["unit"] == "1":
                assert "quantity" not in a, element.get("name")
                continue
            assert "quantity" in a, element.get("name")
            assert quantity_of.setdefault(a["unit"], a["quantity"]) == a["quantity"]
        assert quantity_of["m"] == "Length" and quantity_of["C/kg"] == "ChargeToMassRatio"
        assert quantity_of["rad"] == "Angle" and quantity_of["s"] == "Time"


def test_section_8_relations_hold_dimensionally(described):
    unit = {v.name: pint_unit(v.unit) for v in described.modelVariables if v.unit}
    u = lambda name: unit[name]  # noqa: E731
    a, ell, k, m = u("semi_major_axis"), u("cylinder_length"), u("k_prime"), u("mass_per_length")
    dimensionless = U.dimensionless
    relations = {
        "m' = rho pi a^2 epsilon": (m, u("density") * a ** 2),
        "k' = (pi/4) E*": (k, u("effective_modulus")),
        "t* = sqrt(m'/k')": (u("t_star"), (m / k) ** 0.5),
        "Gamma = m' g / (k' a)": (m * u("gravity") / (k * a), dimensionless),
        "Gamma is dimensionless": (u("Gamma"), dimensionless),
        "tau0 = t0 / t*": (u("charging_time") / u("t_star"), u("tau0")),
        "tau_r = tr / t*": (u("backflow_time") / u("t_star"), u("tau_r")),
        "sqrt(kappa k' a) is a charge density": (u("sigma_scale"),
                                                 (u("interface_capacitance") * k * a) ** 0.5),
        "Sigma0 = sigma0 / sqrt(kappa k' a)": (u("sigma0") / u("sigma_scale"), u("Sigma0")),
        "Sigma0 is dimensionless": (u("Sigma0"), dimensionless),
        "x = a X": (u("x"), a),
        "u = (a / t*) U": (u("u"), a / u("t_star")),
        "omega = Omega / t*": (u("omega"), u("phi") / u("t_star")),
        "F = k' a Psi l": (u("normal_force"), k * a * ell),
        "F' = k' a Psi (inputs)": (u("F_N_ext"), k * a),
        "E = k' a^2 l": (u("energy"), k * a ** 2 * ell),
        "Q' = (a P / N) sum sigma_i": (u("charge_per_length_static"), a * u("sigma_mean_static")),
        "Q = Q' l": (u("charge_sliding"), u("charge_per_length_sliding") * ell),
        "q/m = Q'/m'": (u("charge_to_mass_static"), u("charge_per_length_static") / m),
        "mass = m' l": (u("mass"), m * ell),
        "time in s": (u("time"), u("exit_time")),
    }
    wrong = [name for name, (left, right) in relations.items() if not same_unit(1 * left, 1 * right)]
    assert not wrong


# ---- what the set-up means to the model ------------------------------------------------------


@pytest.mark.parametrize("version", VERSIONS)
def test_calculated_parameters_are_section_8s_numbers(fmu_dir, version):
    s = Slave(fmu_dir(version, SI), version).init()
    g = s.get
    a, ell = g("semi_major_axis"), g("cylinder_length")
    e_star = 1 / ((1 - g("poisson_ratio_particle") ** 2) / g("youngs_modulus_particle") +
                  (1 - g("poisson_ratio_wall") ** 2) / g("youngs_modulus_wall"))
    expected = {
        "effective_modulus": e_star,
        "k_prime": math.pi / 4 * e_star,
        "mass_per_length": g("density") * math.pi * a * a * g("epsilon"),
        "t_star": math.sqrt(g("mass_per_length") / g("k_prime")),
        "Gamma": g("mass_per_length") * g("gravity") / (g("k_prime") * a),
        "tau0": g("charging_time") / g("t_star"),
        "tau_r": g("backflow_time") / g("t_star"),
        "sigma_scale": math.sqrt(g("interface_capacitance") * g("k_prime") * a),
        "Sigma0": abs(g("sigma0")) / g("sigma_scale"),
        # the spheroid's (docs/model.md §8c)
        "mass": 4 / 3 * math.pi * g("density") * a * (g("epsilon") * a) ** 2,
        "drop_speed_scaled": g("drop_speed") / (a / g("t_star")),
    }
    for name, value in expected.items():
        assert g(name) == pytest.approx(value, rel=1e-14), name
    assert g("chute_length_scaled") == 0.3 / a  # the reference case's 0.3 m
    # the reference case: a 1 mm polyethylene grain on steel; t* ~ 0.7 us, Gamma ~ 1e-8
    assert 6e-7 < g("t_star") < 7e-7 and 5e-9 < g("Gamma") < 2e-8
    # a tunable changed while running changes what it means to the model
    s.step_to(1e-4)
    s.set(charging_time=2e-3)
    assert g("tau0") == pytest.approx(2e-3 / g("t_star"), rel=1e-15)
    s.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_a_given_stiffness_is_used_where_stiffness_source_says_so_and_else_is_named_unused(
        fmu_dir, version):
    from_moduli = Slave(fmu_dir(version, SI), version).init()
    moduli = from_moduli.get("k_prime")
    assert from_moduli.messages == []
    from_moduli.free()
    given = Slave(fmu_dir(version, SI), version).init(stiffness_source=0, contact_stiffness=2e9)
    assert given.get("k_prime") == 2e9 and given.messages == []
    given.free()
    # set alone, the earlier interface's way to give it: the moduli's stiffness runs, and a
    # warning names the value not used and the switch that would use it
    unused = Slave(fmu_dir(version, SI), version).init(contact_stiffness=2e9)
    assert unused.get("k_prime") == moduli
    warnings = [m for status, _, m in unused.messages if status == WARNING]
    assert len(warnings) == 1
    assert "contact_stiffness = 2e+09 N/m2 is not used" in warnings[0]
    assert "stiffness_source = 0 (given) uses it" in warnings[0]
    unused.free()


# ---- the SI FMU is the dimensionless one in other units -----------------------------------------

# a soft particle (E* ~ 2.5e4 Pa: Gamma ~ 4e-4, t* ~ 0.14 ms) dropped from 0.04 a, so that a
# short run sees flight, an impact, contact and charging
COMPARED = {"semi_major_axis": 5e-4, "epsilon": 0.5, "density": 950.0,
            "youngs_modulus_particle": 2e4, "tilt": math.pi / 4, "mu": 0.3, "nu": 0.2,
            "charging_time": 1e-4, "backflow_time": 2e-4, "drop_height": 2e-5, "phi0": 0.3,
            "omega0": 50.0, "n_segments": 64, "dt": 5e-4}
MODEL_OF_SI = {"epsilon": "epsilon", "mu": "mu", "nu": "nu", "eta": "eta", "tilt": "beta",
               "phi0": "phi0", "drop_angle": "drop_angle", "n_segments": "n_segments",
               "integrator": "integrator", "dt": "dt",
               "rtol": "rtol", "atol": "atol", "v_reg": "v_reg", "damping_point": "damping_point",
               "stick_model": "stick_model", "mu_roll": "mu_roll", "work_limit": "work_limit",
               "Gamma": "Gamma", "tau0": "tau0", "tau_r": "tau_r",
               "Sigma0": "Sigma0", "chute_length_scaled": "chute_length",
               "drop_speed_scaled": "drop_speed", "Sigma_bd": "Sigma_bd",
               "grain_geometry": "grain_geometry", "Sigma_init": "Sigma_init",
               "breakdown_model": "breakdown_model", "secondary_emission": "secondary_emission",
               "wall_conducting": "wall_conducting", "paschen_gap_scale": "paschen_gap_scale",
               "Sigma_paschen": "Sigma_paschen"}


def dimensionless_scene(si):
    """The dimensionless FMU's parameters of the SI FMU's set-up: its calculated parameters,
    and model.md §8's scales of the rest."""
    a, t_star = si.get("semi_major_axis"), si.get("t_star")
    scene = {model: si.get(name) for name, model in MODEL_OF_SI.items()}
    scene.update(gap0=si.get("drop_height") / a, X0=si.get("x0") / a,
                 Omega0=si.get("omega0") * t_star)
    return scene


def spheroid_area(eps):
    """The prolate spheroid's surface in units of a^2 (docs/model.md §8c)."""
    e = math.sqrt(1 - eps * eps)
    return 2 * math.pi * eps * (eps + math.asin(e) / e) if e > 0 else 4 * math.pi


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator, stick_model, grain", [(0, 0, 0), (1, 0, 0), (1, 1, 0),
                                                            (1, 1, 1), (0, 0, 1)])
def test_si_and_dimensionless_fmus_give_the_same_run(fmu_dir, version, integrator, stick_model,
                                                     grain):
    si = Slave(fmu_dir(version, SI), version).init(**COMPARED, integrator=integrator,
                                                    stick_model=stick_model, grain_geometry=grain)
    model = Slave(fmu_dir(version), version).init(**dimensionless_scene(si))
    a, t_star, sigma0 = si.get("semi_major_axis"), si.get("t_star"), si.get("sigma0")
    scale = si.get("sigma_scale") * math.copysign(1.0, sigma0)
    velocity = a / t_star
    pairs = {  # SI output, its model quantity, the SI output in the model's units
        "x": ("X", lambda v: v / a), "y": ("Y", lambda v: v / a), "phi": ("phi", lambda v: v),
        "u": ("U", lambda v: v / velocity), "v": ("V", lambda v: v / velocity),
        "omega": ("Omega", lambda v: v * t_star),
    }
    if grain == 0:  # the cylinder: the mean densities over its boundary
        pairs.update({"sigma_mean_static": ("Q_static", lambda v: v / sigma0),
                      "sigma_mean_sliding": ("Sigma_mean", lambda v: v / scale)})
    else:  # the spheroid: its charged area and charges (docs/model.md §8c)
        area = spheroid_area(si.get("epsilon"))
        pairs.update({"charged_area": ("charged_area", lambda v: v / a ** 2),
                      "charge_static": ("grain_charge_static", lambda v: v / (sigma0 * a ** 2)),
                      "sigma_mean_sliding": ("grain_charge_sliding",
                                             lambda v: v * area / sigma0)})
    rows_si, rows_model = [], []
    for k in range(1, 41):
        t = k * 5.0 * t_star  # to 200 t*
        si.step_to(t)
        model.step_to(t / t_star)
        rows_si.append([convert(si.get(name)) for name, (_, convert) in pairs.items()])
        rows_model.append([model.get(q) for q, _ in pairs.values()])
    assert model.get("impacts") >= 1 and model.get("Q_static") > 0 and model.get("Sigma_mean") > 0
    assert grain == 0 or model.get("charged_area") > 0
    assert si.get("impacts") == model.get("impacts")
    rows_si, rows_model = np.array(rows_si), np.array(rows_model)
    # relative to each quantity's largest magnitude over the run. Measured: at most 1.3e-16
    # with either integrator, stick model and FMI version (the core runs the same numbers; only the SI
    # FMU's conversions of its outputs round); the test holds them to 1e-14 (about 75 times
    # the measured, for other compilers' rounding)
    error = np.abs(rows_si - rows_model).max(axis=0) / np.abs(rows_model).max(axis=0)
    assert error.max() <= 1e-14, dict(zip(pairs, error))
    if version == 3:  # the per-segment arrays: the model's times sigma0 (docs/model.md §8)
        for si_name, name in (("segment_sigma_static", "segment_charge_static"),
                              ("segment_sigma_sliding", "segment_charge_sliding")):
            mine, theirs = np.array(si.get(si_name)) / sigma0, np.array(model.get(name))
            assert len(mine) == 64 and np.abs(theirs).max() > 0
            assert np.abs(mine - theirs).max() <= 1e-14 * np.abs(theirs).max(), si_name
    si.free()
    model.free()


# ---- the reference case: a 1 mm polyethylene grain leaves a 0.3 m steel chute ----------------


@pytest.mark.parametrize("version", VERSIONS)
def test_reference_case_leaves_the_chute_in_simulate_fmu(fmu_file, version):
    kwargs = {"early_return_allowed": True} if version == 3 else {}
    r = simulate_fmu(fmu_file(version, SI), stop_time=2.0, output_interval=1e-3,
                     start_values={"chute_length": 0.3},
                     output=["x", "u", "exited", "exit_time", "charge_to_mass_static", "impacts"],
                     **kwargs)
    last = r[-1]
    assert bool(last["exited"]) and not any(r["exited"][:-1])
    # the run ends at the exit: its time is the exit time, the centre at the chute's end
    assert float(r["time"][-1]) == float(last["exit_time"])
    assert 0.1 < last["exit_time"] < 2.0
    assert last["x"] == pytest.approx(0.3, rel=1e-9)
    assert last["u"] > 0 and last["impacts"] >= 1
    # polyethylene on steel charges negatively (sigma0 < 0)
    assert last["charge_to_mass_static"] < 0


@pytest.mark.parametrize("version", VERSIONS)
def test_fmpy_reads_inf_as_no_end(fmu_file, fmu_dir, version):
    md = read_model_description(fmu_file(version, SI), validate=True)
    L = next(v for v in md.modelVariables if v.name == "chute_length")
    assert float(L.start) == 0.3 and L.max is None  # the reference case's chute, INF admitted
    s = Slave(fmu_dir(version, SI), version).init(chute_length=math.inf)
    assert s.get("chute_length") == math.inf == s.get("chute_length_scaled")
    s.free()


def test_libcosim_reads_inf_and_stops_at_the_exit(fmu_file):
    """As the dimensionless FMU (test_chute_fmu.py): libcosim takes INF, and a run that
    leaves the chute ends at the step before the exit."""
    fmu = fmu_file(2, SI)
    results = {length: libcosim_run(fmu, 0.01, 1.0, {"chute_length": length},
                                    {"n_segments": 64}, ["chute_length", "x"])
               for length in (math.inf, 0.05)}
    done, now, (L, x) = results[math.inf]
    assert done and now == 1.0 and L == math.inf and x > 0.05
    done, now, (L, x) = results[0.05]
    assert not done and now < 1.0 and L == 0.05 and x < 0.05


# ---- bad input -----------------------------------------------------------------------------------


@pytest.mark.parametrize("version", VERSIONS)
def test_an_si_value_out_of_its_range_is_refused_naming_it(fmu_dir, version):
    s = Slave(fmu_dir(version, SI), version)
    assert status_of(s.set, density=2e5) == ERROR
    message = s.errors()[-1]
    assert "density" in message and "200000" in message and "100000" in message
    assert s.get("density") == 950.0
    s.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_a_retired_value_reference_is_refused_saying_what_took_its_place(fmu_dir, version):
    # the per-model charge outputs the registry's rows make, at 510 + slot, ...: their former
    # value references stay retired (si_quantities.def's TRIBO_RETIRED rows)
    s = Slave(fmu_dir(version, SI), version).init()
    real = s.fmu.getReal if version == 2 else s.fmu.getFloat64
    assert status_of(real, [213]) == ERROR
    assert ("value reference 213 is retired (it was charge_static's): charge_static is value "
            "reference 510") in s.errors()[-1]
    assert s.variables["charge_static"].valueReference == 510
    assert s.variables["sigma_mean_sliding"].valueReference == 541
    s.free()


# (what is set, the model's parameter out of range, the SI inputs the message must name)
DERIVED_OUT_OF_RANGE = [
    # a particle so soft and heavy that gravity out-weighs its stiffness: Gamma ~ 2e4 > 10
    ({"youngs_modulus_particle": 1e3, "density": 1e5, "semi_major_axis": 0.05},
     "Gamma", ["youngs_modulus_particle", "density", "semi_major_axis", "gravity"]),
    # so small and stiff that its weight is nothing: Gamma ~ 1e-19 < 1e-12
    ({"semi_major_axis": 1e-7, "density": 1.0, "youngs_modulus_particle": 1e13,
      "youngs_modulus_wall": 1e13, "charging_time": 1e-9, "backflow_time": 1e-9},
     "Gamma", ["semi_major_axis", "density", "gravity"]),
    # a charging time far above the model's time scale: 100 s against t* ~ 1e-9 s
    ({"charging_time": 100.0, "semi_major_axis": 1e-6}, "tau0", ["charging_time", "semi_major_axis"]),
]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("bad, derived, named", DERIVED_OUT_OF_RANGE)
def test_derived_numbers_out_of_the_models_range_are_refused(fmu_dir, version, bad, derived, named):
    """Refused at the end of initialization (where the dimensionless FMU refuses a scene),
    with the model's parameter, its value and range and the SI inputs that made it; the
    instance stays in Initialization Mode, where a corrected set-up initializes."""
    s = Slave(fmu_dir(version, SI), version)
    s.set(**bad)
    if version == 2:
        s.fmu.setupExperiment()
        s.fmu.enterInitializationMode()
    else:
        s.fmu.enterInitializationMode()
    assert status_of(s.fmu.exitInitializationMode) == ERROR
    message = s.errors()[-1]
    assert f"{derived} = " in message and "valid range" in message, message
    assert all(f"{name} = " in message for name in named), message
    assert status_of(s.get, "t_star") == ERROR  # nothing to compute it from
    fixed = {name: s.variables[name].start for name in bad}
    s.set(**{name: float(value) for name, value in fixed.items()})
    assert status_of(s.fmu.exitInitializationMode) == OK, s.errors()
    s.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_an_input_beyond_the_models_range_is_refused_while_running(fmu_dir, version):
    # a = 0.1 mm: 10 k' a (9.9e5 N/m) lies inside the declared range, +-4.9e6 N/m; without
    # rolling resistance: pressed this hard, the grain comes to rest at once and its run ends
    # there (docs/model.md section 3c)
    s = Slave(fmu_dir(version, SI), version).init(semi_major_axis=1e-4, mu_roll=0.0)
    unit = s.get("k_prime") * s.get("semi_major_axis")  # k' a, N/m
    s.set(F_N_ext=-5 * unit)
    assert status_of(s.set, F_N_ext=-11 * unit) == ERROR
    message = s.errors()[-1]
    assert "F_N_ext" in message and "k' a" in message, message
    assert s.get("F_N_ext") == -5 * unit
    # (a short step: pressed this hard the grain's rocking costs FMI 2.0's whole work limit,
    # which it cannot continue past, in about 7e-5 s)
    assert s.step_to(2e-5)
    s.free()


# ---- FMU states ------------------------------------------------------------------------------------


@pytest.mark.parametrize("version", VERSIONS)
def test_a_state_of_the_si_fmu_restores_into_a_fresh_instance(fmu_dir, version):
    params = dict(COMPARED, integrator=1)
    s = Slave(fmu_dir(version, SI), version).init(**params)
    t_star = s.get("t_star")
    s.step_to(20 * t_star)
    state = s.serialize(s.get_state())
    s.step_to(60 * t_star)
    expected = s.get_many(["x", "y", "charge_static", "charge_sliding"])
    other = Slave(fmu_dir(version, SI), version)
    other.set_state(other.deserialize(state))
    assert other.get("youngs_modulus_particle") == 2e4 and other.get("t_star") == t_star
    other.t = 20 * t_star
    other.step_to(60 * t_star)
    assert other.get_many(["x", "y", "charge_static", "charge_sliding"]) == expected
    s.free()
    other.free()


@pytest.mark.parametrize("version", VERSIONS)
def test_stick_model_follows_the_integrator_and_the_dashpot_until_it_is_set(fmu_dir, version):
    """The SI default, the rigid stick, needs CVODE and the contact point's dashpot: left
    unset, stick_model follows integrator and damping_point (the fixed step or the centre's
    dashpot alone is a valid set-up); set explicitly, the rigid stick with either is refused
    at the set call that makes the conflict, in either order or in one call."""
    s = Slave(fmu_dir(version, SI), version, name=SI)
    integer = s.fmu.setInteger if version == 2 else s.fmu.setInt64
    vr = {n: s.variables[n].valueReference for n in ("integrator", "damping_point", "stick_model")}
    assert s.get("stick_model") == 1
    s.set(integrator=0)
    assert s.get("stick_model") == 0
    s.set(integrator=1)
    assert s.get("stick_model") == 1
    s.set(damping_point=1)
    assert s.get("stick_model") == 0
    s.set(damping_point=0, stick_model=1)  # now set explicitly
    assert status_of(s.set, integrator=0) == ERROR
    assert s.errors()[-1].endswith(
        "stick_model = 1 (rigid), set explicitly, does not go with integrator = 0 and "
        "damping_point = 0: the rigid stick needs CVODE (integrator = 1 or 2) and the contact "
        "point's dashpot (damping_point = 0); set stick_model = 0 (compliant), or leave it "
        "unset to follow them")
    assert s.get("integrator") == 1
    s.fmu.reset()
    assert status_of(integer, [vr["integrator"], vr["stick_model"]], [0, 1]) == ERROR
    assert (s.get("integrator"), s.get("stick_model")) == (1, 1)
    s.set(integrator=0)
    assert status_of(s.set, stick_model=1) == ERROR
    # a state keeps whether stick_model was set: restored, it still follows
    state = s.get_state()
    fresh = Slave(fmu_dir(version, SI), version, name=SI)
    fresh.set_state(fresh.deserialize(s.serialize(state)))
    fresh.set(integrator=2)
    assert fresh.get("stick_model") == 1
    fresh.init()
    assert fresh.do_step(0.0, 1e-6)[0] == OK
