"""The separator FMUs (tribo_separator_fmi2, tribo_separator_fmi3: the free-fall separator of
docs/model.md §10, src/separator/separator_quantities.def; docs/separator.md).

fmpy finds nothing wrong with them; a grain released at a known state lands where §10's
closed form puts it in vacuum (the bin, x, the flight time), or is caught on the plate it
gives; refused values name the variable, the value and the range; two instances side by
side are independent; FMU states restore a run bit for bit; and the SI chute's FMU coupled
to the separator's by a master loop (the chute's exit releases the grain with the chute's
exit velocity and charge-to-mass ratio) collects the grain on the side its charge's sign
gives."""

import math
import sys

import pytest
from fmpy.validation import validate_fmu

from tribo_fmu import ERROR, OK, VERSIONS, Slave, status_of

SEPARATOR = "tribo_separator"
# the table's defaults (src/separator/separator_quantities.def)
GAP, HEIGHT, VOLTAGE, N_BINS, A, G, TILT = 0.1, 0.5, 30e3, 10, 5e-4, 9.81, math.radians(30)
VACUUM = {"air_density": 0.0, "air_viscosity": 0.0}
STEP = 1e-3
# Every communication step restarts CVODE (docs/separator.md): in vacuum, 1 ms steps at the
# default rtol (1e-8) move the flight time by 1.4e-6 of itself, at rtol 1e-12 by 1.6e-9
# (measured); the closed form is held to 1e-8 at rtol 1e-12.
EXACT = {"rtol": 1e-12}
CLOSE = 1e-8


def separator(fmu_dir, version, name="separator"):
    return Slave(fmu_dir(version, SEPARATOR), version, name=name)


def run_to_end(s, t_end=5.0, h=STEP):
    """Step on a grid from s.t until the FMU ends the run (False if it did not by t_end)."""
    k = 0
    start = s.t
    while s.t < t_end:
        k += 1
        if not s.step_to(start + k * h):
            return True
    return False


def release(s, t_release, **inputs):
    """Hold the grain until t_release, then release it with the inputs given."""
    if t_release > 0:
        assert s.step_to(t_release)
        assert s.get("has_released") == 0 and s.get("z") == 0.0
    s.set(released=True, **inputs)


def entry_velocity(u, v, beta=TILT):
    """The chute frame's (u down-slope, v away from the chute) in the lab frame
    (docs/model.md §10): (horizontal, vertical)."""
    return u * math.cos(beta) + v * math.sin(beta), -u * math.sin(beta) + v * math.cos(beta)


def bin_of(x, gap=GAP, n=N_BINS):
    return min(max(math.floor((x + gap / 2) / gap * n), 0), n - 1) + 1


@pytest.mark.parametrize("version", VERSIONS)
def test_fmpy_validation_finds_no_problem(fmu_file, version):
    assert validate_fmu(fmu_file(version, SEPARATOR)) == []


@pytest.mark.parametrize("direction", [0, 1])
@pytest.mark.parametrize("q_per_m", [1e-6, -1e-6, 0.0])
@pytest.mark.parametrize("version", VERSIONS)
def test_grain_lands_in_the_bin_of_the_closed_form(fmu_dir, version, q_per_m, direction):
    """In vacuum (docs/model.md §10): x = x0 + vx0 t + (q/m) E_x t^2 / 2, z = vz0 t - g t^2 / 2,
    landing at T = (vz0 + sqrt(vz0^2 + 2 g H)) / g, E_x = -U / w."""
    # across the gap, slower: the horizontal velocity moves the grain towards +x
    u, v = (0.5, 0.1) if direction == 0 else (0.05, 0.01)
    x0, t_release = 0.004, 0.05
    s = separator(fmu_dir, version)
    s.init(chute_direction=direction, x_entry=x0, **VACUUM, **EXACT)
    release(s, t_release, u_entry=u, v_entry=v, charge_to_mass=q_per_m)
    assert run_to_end(s)

    horizontal, vz0 = entry_velocity(u, v)
    vx0 = horizontal if direction == 1 else 0.0
    T = (vz0 + math.sqrt(vz0 ** 2 + 2 * G * HEIGHT)) / G
    x_end = x0 + vx0 * T + 0.5 * q_per_m * (-VOLTAGE / GAP) * T ** 2
    # it lands, and not within the integration's error of a bin's edge
    assert abs(x_end) < GAP / 2 - A
    edge = (x_end + GAP / 2) / GAP * N_BINS % 1
    assert min(edge, 1 - edge) * GAP / N_BINS > 1e-6
    assert s.get("ended") and s.get("landed") and s.get("electrode") == 0
    assert s.get("bin") == bin_of(x_end)
    assert s.get("x_end") == pytest.approx(x_end, rel=CLOSE, abs=1e-10)
    assert s.get("z_end") == -HEIGHT and s.get("z") == -HEIGHT
    assert s.get("flight_time") == pytest.approx(T, rel=CLOSE)
    assert s.t == pytest.approx(t_release + T, rel=CLOSE)
    assert s.get("q_per_m") == q_per_m
    vy0 = 0.0 if direction == 1 else horizontal
    assert s.get("y") == pytest.approx(vy0 * T, rel=CLOSE, abs=1e-12)
    # the run is over: a further step is refused, saying how it ended
    assert status_of(s.fmu.doStep, s.t, STEP) == ERROR
    assert f"the grain landed in bin {bin_of(x_end)} of {N_BINS}" in s.errors()[-1]


@pytest.mark.parametrize("version", VERSIONS)
def test_grain_is_caught_on_the_plate_of_the_closed_form(fmu_dir, version):
    """A strong charge reaches the plate its sign gives first: 1/2 |(q/m) E_x| t_c^2 = w/2 - a
    (x0 = 0, no velocity across the gap), at z = vz0 t_c - g t_c^2 / 2."""
    u, q_per_m = 0.5, 1e-4
    s = separator(fmu_dir, version)
    s.init(**VACUUM, **EXACT)
    release(s, 0.0, u_entry=u, charge_to_mass=q_per_m)
    assert run_to_end(s)
    _, vz0 = entry_velocity(u, 0.0)
    t_c = math.sqrt(2 * (GAP / 2 - A) / abs(q_per_m * VOLTAGE / GAP))
    assert s.get("ended") and not s.get("landed") and s.get("bin") == 0
    assert s.get("electrode") == -1  # a positive grain drifts to -x for U > 0
    assert s.get("x_end") == -(GAP / 2 - A)
    assert s.get("z_end") == pytest.approx(vz0 * t_c - G * t_c ** 2 / 2, rel=CLOSE)
    assert s.get("flight_time") == pytest.approx(t_c, rel=CLOSE)


@pytest.mark.parametrize("version", VERSIONS)
def test_bad_inputs_and_parameters_are_refused_naming_them(fmu_dir, version):
    s = separator(fmu_dir, version)
    for name, value, text in [
            ("charge_to_mass", 2.0, "charge_to_mass = 2 is invalid: the valid range is -1 <= "
                                    "charge_to_mass <= 1"),
            ("u_entry", -1e4, "u_entry = -10000 is invalid: the valid range is -1000 <= u_entry "
                              "<= 1000"),
            ("v_entry", math.nan, "v_entry = nan is invalid"),
            ("gap", 0.0, "gap = 0 is invalid: the valid range is 0.002 <= gap <= 10"),
            ("n_bins", 0, "n_bins = 0 is invalid: the valid range is an integer with 1 <= "
                          "n_bins <= 100000")]:
        assert status_of(s.set, **{name: value}) == ERROR, name
        assert text in s.errors()[-1], (name, s.errors()[-1])
    # a refused value changes nothing
    assert s.get("charge_to_mass") == 0.0 and s.get("gap") == GAP
    # the combinations are checked when initialization ends: the grain must fit the gap
    assert status_of(s.init, semi_major_axis=0.04, gap=0.05) == ERROR
    assert "semi_major_axis" in s.errors()[-1] and "gap" in s.errors()[-1]
    s.free()
    s = separator(fmu_dir, version)
    s.init()
    # between steps too: the input keeps its value
    s.set(charge_to_mass=1e-6)
    assert status_of(s.set, charge_to_mass=-1.5) == ERROR
    assert "charge_to_mass = -1.5 is invalid" in s.errors()[-1]
    assert s.get("charge_to_mass") == 1e-6
    # a fixed parameter is not set while running
    assert status_of(s.set, voltage=1e3) == ERROR
    assert "voltage" in s.errors()[-1] and "fixed parameter" in s.errors()[-1]


def test_fmi2_boolean_is_fmi2true_or_fmi2false(fmu_dir):
    s = separator(fmu_dir, 2)
    s.init(**VACUUM)
    vr = s.variables["released"].valueReference
    for value in (2, -1, 15):
        assert status_of(s.fmu.setBoolean, [vr], [value]) == ERROR
        assert s.errors()[-1] == (f"fmi2SetBoolean: released = {value} is not an fmi2Boolean: "
                                  "it must be fmi2True (1) or fmi2False (0)")
        assert s.get("released") == 0
    s.fmu.setBoolean([vr], [1])
    assert s.step_to(STEP) and s.get("has_released") == 1


@pytest.mark.parametrize("version", VERSIONS)
def test_a_viscosity_at_its_smallest_gives_numbers_after_an_ok_step(fmu_dir, version):
    """air_viscosity = 5e-324 Pa.s, inside its declared range: the relaxation time and the
    Reynolds number overflow a double, and read as the largest one (the drag is Newton's)."""
    s = separator(fmu_dir, version)
    s.init(air_viscosity=5e-324)
    assert s.get("relaxation_time") == sys.float_info.max
    release(s, 0.0, u_entry=0.4, v_entry=-0.2)
    status, _, _ = s.do_step(0.0, 0.01)
    assert status == OK
    assert s.get("reynolds") == sys.float_info.max
    outputs = [v.name for v in s.md.modelVariables
               if v.causality in ("output", "calculatedParameter")]
    assert all(math.isfinite(x) for x in s.get_many(outputs).values())


def flight(fmu_dir, version, q_per_m, voltage=VOLTAGE, name="separator"):
    s = separator(fmu_dir, version, name=name)
    s.init(voltage=voltage)
    release(s, 0.0, u_entry=0.4, v_entry=-0.2, charge_to_mass=q_per_m)
    return s


OUTPUTS = ("x", "y", "z", "vx", "vy", "vz", "bin", "electrode", "x_end", "z_end", "flight_time")


@pytest.mark.parametrize("version", VERSIONS)
def test_two_instances_side_by_side_are_independent(fmu_dir, version):
    """Interleaved steps of two instances of other set-ups give each what it gives alone
    (with drag: the default air)."""
    a = flight(fmu_dir, version, 2e-6, name="a")
    b = flight(fmu_dir, version, -3e-6, voltage=20e3, name="b")
    going = {"a": True, "b": True}
    k = 0
    while going["a"] or going["b"]:
        k += 1
        for key, s in (("a", a), ("b", b)):
            if going[key]:
                going[key] = s.step_to(k * STEP)
    together = [s.get_many(OUTPUTS) | {"t": s.t} for s in (a, b)]
    alone = []
    for q, voltage in ((2e-6, VOLTAGE), (-3e-6, 20e3)):
        s = flight(fmu_dir, version, q, voltage=voltage)
        assert run_to_end(s)
        alone.append(s.get_many(OUTPUTS) | {"t": s.t})
    assert together == alone
    assert together[0]["x_end"] < 0 < together[1]["x_end"]


@pytest.mark.parametrize("version", VERSIONS)
def test_fmu_state_restores_the_run_bit_for_bit(fmu_dir, version):
    s = flight(fmu_dir, version, 2e-6)
    assert s.step_to(0.1)
    state = s.get_state()
    data = s.serialize(state)
    assert run_to_end(s)
    first = s.get_many(OUTPUTS) | {"t": s.t}
    s.set_state(state)
    s.t = 0.1
    assert s.get("ended") == 0 and s.get("time") == 0.1
    assert run_to_end(s)
    assert s.get_many(OUTPUTS) | {"t": s.t} == first
    # serialized, into a fresh instance of another set-up
    fresh = separator(fmu_dir, version, name="fresh")
    fresh.init(voltage=1e3)
    fresh.set_state(fresh.deserialize(data))
    fresh.t = 0.1
    assert run_to_end(fresh)
    assert fresh.get_many(OUTPUTS) | {"t": fresh.t} == first
    s.free_state(state)


@pytest.mark.parametrize("version", VERSIONS)
def test_a_negative_zero_set_after_a_read_in_initialization_restores(fmu_dir, version):
    """x_entry = -0.0 set in Initialization Mode after an output was read there (which made
    the core, at +0.0): the core is made again at -0.0, so that every later state, whose
    scene says -0.0, is taken back (-0.0 == +0.0 once kept the core, and every restore was
    refused: "a grain not released is not at the entry")."""
    s = separator(fmu_dir, version)
    if version == 2:
        s.fmu.setupExperiment(startTime=0.0)
        s.fmu.enterInitializationMode()
    else:
        s.fmu.enterInitializationMode(startTime=0.0)
    assert s.get("x") == 0.0
    s.set(x_entry=-0.0)
    s.fmu.exitInitializationMode()
    s.t = 0.0
    assert s.step_to(0.01)
    state = s.get_state()
    assert status_of(s.set_state, state) == OK, s.errors()
    assert status_of(s.set_state, s.deserialize(s.serialize(state))) == OK, s.errors()
    assert math.copysign(1.0, s.get("x")) == -1.0


# ---- coupled to the SI chute ------------------------------------------------------------------

# the chute's outputs -> the separator's inputs (docs/separator.md, "Coupling")
CONNECTIONS = {"exited": "released", "u": "u_entry", "v": "v_entry",
               "charge_to_mass": "charge_to_mass"}


def coupled_run(fmu_dir, version, sigma0, h=STEP, t_end=3.0):
    """The SI chute, then the separator, by a master loop: both step from t on a grid of h;
    where the chute's step ends early at its exit (t_exit), the separator steps to t_exit
    too, and from then on takes the chute's outputs there, frozen, as its inputs (the grain
    released at the exit exactly). Returns (the chute's exit time, the chute, the
    separator)."""
    chute = Slave(fmu_dir(version, "tribo_si"), version, name="chute")
    # the sliding model alone: the charge models are alternative laws (docs/model.md §5); a
    # 1 mm grain (the spheroid, §8c) leaves the 0.3 m chute at a few 1e-7 C/kg, after eight
    # impacts
    chute.init(chute_length=0.3, charge_model_static=0, charge_to_mass_model=2, sigma0=sigma0)
    sep = Slave(fmu_dir(version, SEPARATOR), version, name="separator")
    # the chute's tilt and grain, bound to one value; 10 kV keeps the grain off the plates
    sep.init(tilt=chute.get("tilt"), semi_major_axis=chute.get("semi_major_axis"),
             epsilon=chute.get("epsilon"), density=chute.get("density"), voltage=10e3)
    t_exit = None
    k = 0
    while True:
        k += 1
        t = k * h
        if t_exit is None:
            chute_going = chute.step_to(t)
            if not chute_going:
                t = t_exit = chute.t  # the step ended at the exit
        if not sep.step_to(t):
            break
        # the connections, at the communication point: the chute's values there
        sep.set(**{dst: chute.get(src) for src, dst in CONNECTIONS.items()})
        if t_exit is not None and t_exit == t:
            k = t_exit / h  # back onto a grid from the exit
        assert t < t_end, "the grain does not reach the bins"
    return t_exit, chute, sep


@pytest.mark.parametrize("sigma0", [-1e-5, 1e-5])
@pytest.mark.parametrize("version", VERSIONS)
def test_coupled_to_the_si_chute_the_grain_lands_on_its_charges_side(fmu_dir, version, sigma0):
    t_exit, chute, sep = coupled_run(fmu_dir, version, sigma0)
    q = chute.get("charge_to_mass")
    assert chute.get("exited") and t_exit == pytest.approx(chute.get("exit_time"), rel=1e-12)
    # a charge whose sign is the interface's, large enough to move the grain across bins
    assert math.copysign(1, q) == math.copysign(1, sigma0) and abs(q) > 1e-7
    assert sep.get("q_per_m") == q
    assert sep.get("has_released") and sep.get("landed")
    # released at the exit: the flight starts there
    assert sep.t - sep.get("flight_time") == pytest.approx(t_exit, abs=1e-12)
    # U > 0: a positive grain drifts to -x, into the bins from the negative plate's side
    assert math.copysign(1, sep.get("x_end")) == -math.copysign(1, q)
    assert (sep.get("bin") <= N_BINS // 2) == (q > 0)
