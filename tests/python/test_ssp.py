"""The separation line's SSP package, build/ssp/tribo_line.ssp (python/tribo/ssp.py;
docs/separator.md, "The SSP package"): the SI chute's FMU feeding the separator's.

- Its structure: the FMUs are the build's, the .ssd and .ssv files are valid SSP 1.0 (the
  schemas fmpy ships), every connection joins an output to an input of one type and unit as
  the FMUs declare them, every bound value is a parameter of its FMU.
- Run from the .ssp alone: ecos (ecospy) and libcosim (libcosimpy) run it to the stop time,
  the grain landed (both components hold at their run's end: hold_at_end), with the static
  model's ratio on the connection (charge_to_mass_model = 1, an FMI Integer both set).
- Both land where a direct two-step fmpy run does (the chute to its exit, then the separator
  released there with the chute's exit values) within the co-simulation's measured error.
"""

import math
import subprocess
import sys
import xml.etree.ElementTree as ET
import zipfile

import pytest
from fmpy import read_model_description

from conftest import built
from tribo import ssp
from tribo_fmu import Slave

NS = ssp.NAMESPACES
SEPARATOR_OUTPUTS = ("x_end", "z_end", "flight_time", "q_per_m")


@pytest.fixture(scope="module")
def package():
    return built("ssp", "tribo_line.ssp")


def members(path):
    with zipfile.ZipFile(path) as z:
        return {name: z.read(name) for name in z.namelist()}


def ssd_of(path):
    return ET.fromstring(members(path)["SystemStructure.ssd"])


def components(root):
    return {c.get("name"): c for c in root.iter(f"{{{NS['ssd']}}}Component")}


def ssv_values(data):
    """name -> value of an .ssv (Real as float, Integer as int, Boolean as bool)."""
    values = {}
    for p in ET.fromstring(data).iter(f"{{{NS['ssv']}}}Parameter"):
        (v,) = list(p)
        kind = v.tag.split("}")[1]
        values[p.get("name")] = {"Real": float, "Integer": int,
                                 "Boolean": lambda s: s == "true"}[kind](v.get("value"))
    return values


def bound_values(path):
    """The component's name -> its bound values, as the package holds them."""
    files = members(path)
    out = {}
    for name, c in components(ssd_of(path)).items():
        out[name] = {}
        for binding in c.iter(f"{{{NS['ssd']}}}ParameterBinding"):
            out[name] |= ssv_values(files[binding.get("source")])
    return out


# ---- the structure ---------------------------------------------------------------------------

def test_the_package_holds_the_builds_fmus_and_its_parameter_sets(package):
    files = members(package)
    assert sorted(files) == ["SystemStructure.ssd", "resources/chute.ssv",
                             "resources/separator.ssv", "resources/tribo_separator_fmi2.fmu",
                             "resources/tribo_si_fmi2.fmu"]
    for name in ("tribo_si_fmi2", "tribo_separator_fmi2"):
        with open(built("fmu", f"{name}.fmu"), "rb") as f:
            assert files[f"resources/{name}.fmu"] == f.read(), name
    sources = {n: c.get("source") for n, c in components(ssd_of(package)).items()}
    assert sources == {"chute": "resources/tribo_si_fmi2.fmu",
                       "separator": "resources/tribo_separator_fmi2.fmu"}


def test_the_ssd_and_ssv_files_are_valid_ssp_1_0(package):
    """Against the SSP 1.0 schemas fmpy ships (fmpy/ssp/schema)."""
    from fmpy.ssp.ssd import validate_tree
    from lxml import etree

    files = members(package)
    validate_tree(etree.fromstring(files["SystemStructure.ssd"]), "SystemStructureDescription.xsd")
    for name in ("resources/chute.ssv", "resources/separator.ssv"):
        validate_tree(etree.fromstring(files[name]), "SystemStructureParameterValues.xsd")
    root = ssd_of(package)
    assert root.get("version") == "1.0"
    experiment = root.find("ssd:DefaultExperiment", NS)
    assert float(experiment.get("startTime")) == 0.0
    assert float(experiment.get("stopTime")) == ssp.STOP_TIME
    step = experiment.find("ssd:Annotations/ssc:Annotation/osp:Algorithm/osp:FixedStepAlgorithm", NS)
    assert float(step.get("baseStepSize")) == ssp.STEP_SIZE


def fmu_variables(name):
    md = read_model_description(built("fmu", f"{name}.fmu"))
    units = {u.name: u.baseUnit for u in md.unitDefinitions}
    return {v.name: v for v in md.modelVariables}, units


def test_connections_join_outputs_to_inputs_of_one_type_and_unit(package):
    root = ssd_of(package)
    fmus = {"chute": fmu_variables("tribo_si_fmi2"), "separator": fmu_variables("tribo_separator_fmi2")}
    ssd_units = {u.get("name"): {k: int(v) for k, v in u.find("ssc:BaseUnit", NS).attrib.items()}
                 for u in root.findall("ssd:Units/ssc:Unit", NS)}
    connectors = {}
    for name, c in components(root).items():
        variables, units = fmus[name]
        for connector in c.findall("ssd:Connectors/ssd:Connector", NS):
            v = variables[connector.get("name")]
            (kind,) = list(connector)
            # the connector is the FMU's variable: its causality, type and unit
            assert connector.get("kind") == v.causality, connector.get("name")
            assert kind.tag == f"{{{NS['ssc']}}}{v.type}", connector.get("name")
            assert kind.get("unit") == v.unit, connector.get("name")
            if v.unit is not None:
                fmu_base = {k: getattr(units[v.unit], k) for k in ssd_units[v.unit]}
                assert fmu_base == ssd_units[v.unit], v.unit
                # no exponent the FMU declares is left out
                assert all(getattr(units[v.unit], k) in (0, None) for k in
                           ("kg", "m", "s", "A", "K", "mol", "cd", "rad") if k not in ssd_units[v.unit])
            connectors[(name, v.name)] = v
    made = [(c.get("startElement"), c.get("startConnector"), c.get("endElement"), c.get("endConnector"))
            for c in root.findall("ssd:System/ssd:Connections/ssd:Connection", NS)]
    assert made == [("chute", src, "separator", dst) for src, dst in ssp.CONNECTIONS]
    for a_comp, a, b_comp, b in made:
        out, inp = connectors[(a_comp, a)], connectors[(b_comp, b)]
        assert (out.causality, inp.causality) == ("output", "input")
        assert (out.type, out.unit) == (inp.type, inp.unit)
    assert ssd_units["m/s"] == {"m": 1, "s": -1} and ssd_units["C/kg"] == {"kg": -1, "s": 1, "A": 1}


def test_the_parameter_sets_bind_parameters_of_each_fmu(package):
    """One set, "line", a file per component; the shared values equal in both; the chute's
    connection carries the static model's ratio (the models are alternative laws of one
    charge), chosen by an Integer, the Enumeration switches left alone (no importer here sets
    them); both hold at their run's end."""
    values = bound_values(package)
    for name, fmu in (("chute", "tribo_si_fmi2"), ("separator", "tribo_separator_fmi2")):
        variables, _ = fmu_variables(fmu)
        for key in values[name]:
            assert variables[key].causality == "parameter", (name, key)
    for key, value in ssp.SHARED.items():
        assert values["chute"][key] == values["separator"][key] == value, key
    assert values["chute"]["chute_length"] == 0.3
    assert values["chute"]["charge_to_mass_model"] == 1
    assert not any(k.startswith("charge_model") for k in values["chute"])
    assert values["chute"]["hold_at_end"] is True and values["separator"]["hold_at_end"] is True
    names = {ET.fromstring(data).get("name") for path, data in members(package).items()
             if path.endswith(".ssv")}
    assert names == {ssp.PARAMETER_SET}


def test_the_builder_refuses_what_is_not_a_parameter(tmp_path):
    with pytest.raises(ValueError, match="exited is not a parameter"):
        ssp.build(tmp_path / "x.ssp", built("fmu", "tribo_si_fmi2.fmu"),
                  built("fmu", "tribo_separator_fmi2.fmu"), chute_parameters={"exited": 1})
    with pytest.raises(ValueError, match="FMI 2.0 chute with an FMI 3.0 separator"):
        ssp.build(tmp_path / "x.ssp", built("fmu", "tribo_si_fmi2.fmu"),
                  built("fmu", "tribo_separator_fmi3.fmu"))


# ---- the reference: a direct two-step fmpy run --------------------------------------------------

def direct_run(fmu_dir, chute_values, separator_values):
    """The chute to its exit in one step (its exit does not depend on the communication
    points: the same to the last bit on a 1 ms grid), then the separator released at the exit
    with the chute's exit values, to its end in one step (no CVODE restart). Neither holds at
    its end (hold_at_end does not change the run before it)."""
    chute_values = {k: v for k, v in chute_values.items() if k != "hold_at_end"}
    separator_values = {k: v for k, v in separator_values.items() if k != "hold_at_end"}
    chute = Slave(fmu_dir(2, "tribo_si"), 2, name="chute").init(**chute_values)
    assert not chute.step_to(10.0)
    out = {n: chute.get(n) for n in ("exit_time", "u", "v", "charge_to_mass",
                                     "charge_to_mass_static", "charge_to_mass_sliding")}
    sep = Slave(fmu_dir(2, "tribo_separator"), 2, name="separator").init(**separator_values)
    assert sep.step_to(chute.t)
    sep.set(released=True, u_entry=out["u"], v_entry=out["v"], charge_to_mass=out["charge_to_mass"])
    assert not sep.step_to(chute.t + 10.0)
    out |= sep.get_many(SEPARATOR_OUTPUTS + ("bin", "landed", "electrode"))
    out["end_time"] = sep.t
    chute.free()
    sep.free()
    return out


def test_the_packages_set_up_lands_within_its_default_experiment(fmu_dir, package):
    """The line as the package sets it up (the static model's ratio), run directly: the grain
    (with the SI FMU's default rolling resistance, mu_roll = 0.01) leaves the 0.3 m chute at
    0.464 s with -6.7e-9 C/kg and lands 0.368 s later in bin 6 of 10 at x_end = +101 um
    (30 kV), before the default experiment's stop time, 1.5 s."""
    values = bound_values(package)
    ref = direct_run(fmu_dir, values["chute"], values["separator"])
    assert ref["charge_to_mass"] == ref["charge_to_mass_static"] < 0
    assert ref["charge_to_mass_sliding"] < ref["charge_to_mass"]  # both run; one is carried
    assert ref["landed"] and ref["bin"] == 6 and ref["x_end"] > 0  # U > 0: a negative grain to +x
    assert ref["exit_time"] == pytest.approx(0.4637, abs=1e-4)
    assert ref["end_time"] == pytest.approx(0.8321, abs=1e-4) and ref["end_time"] < ssp.STOP_TIME


# ---- ecos -----------------------------------------------------------------------------------------

def ecos_run(path, step):
    """The package in ecos from the .ssp file alone, its parameter set applied, in steps of
    `step` to the default experiment's stop time. Returns the separator's outputs, the
    chute's, and the communication points at which ecos first saw the grain released and
    ended."""
    from ecospy import EcosSimulation, SimulationListener

    class Watch(SimulationListener):
        def __init__(self, sim):
            self.sim, self.released, self.ended = sim, None, None

        def post(self, info):
            if self.released is None and self.sim.get_bool("separator::has_released"):
                self.released = info.time
            if self.ended is None and self.sim.get_bool("separator::ended"):
                self.ended = info.time

    with EcosSimulation(ssp_path=str(path), step_size=step) as sim:
        watch = Watch(sim)
        sim.add_listener("watch", watch)
        assert sim.init(parameter_set=ssp.PARAMETER_SET)
        sim.step(round(ssp.STOP_TIME / step))
        out = {n: sim.get_real(f"separator::{n}") for n in SEPARATOR_OUTPUTS}
        out |= {n: sim.get_integer(f"separator::{n}") for n in ("bin",)}
        out |= {n: sim.get_bool(f"separator::{n}") for n in ("has_released", "ended", "landed")}
        out |= {n: sim.get_real(f"chute::{n}") for n in ("exit_time", "charge_to_mass",
                                                         "charge_to_mass_sliding", "chute_length")}
        out |= {"released_seen": watch.released, "ended_seen": watch.ended, "time": sim.get_time()}
    return out


# The agreement with the direct run, of the package as built (30 kV, the static model's ratio:
# bin 6, x_end = +74.0 um, flight 0.3604 s). Measured against the direct run, ecos 0.7.2 and
# libcosim (libcosimpy 0.0.6) alike, to the last digit:
#
#   step    x_end        flight_time   release lag (s)
#   1e-2    -1.7e-12 m   +1.3e-7 s     1.05e-2 (seen at 0.490)
#   1e-3    +1.2e-11 m   -4.5e-7 s     1.5e-3  (seen at 0.481)
#   1e-4    +6.5e-11 m   -2.6e-6 s     1.8e-4  (seen at 0.4797)
#
# The chute's exit (time, velocity, charge) is the same to the last bit at every step. The
# release lags: the tools pass the chute's outputs at the communication points, so the
# separator is released at the first one after the exit, up to one step late; but it holds
# the grain at the entry until then and releases it with the exit's velocity, so the lag
# delays the whole flight and moves the landing position not at all. What is left is CVODE's
# restart at every communication step (docs/separator.md, "Communication steps and
# accuracy"), which grows with the number of steps. Tolerances: 3x the error measured at the
# package's step, 1e-3 s (x_end 1.65e-10 m in both tools; the flight time 3.7e-7 s, held to
# the 1.3e-6 s of an earlier measurement, the larger).
X_END_TOL, FLIGHT_TOL = 5e-10, 1.3e-6


def assert_lands_as_the_direct_run(got, ref):
    assert got["landed"] and ref["landed"] and got["bin"] == ref["bin"] == 6
    assert got["q_per_m"] == ref["charge_to_mass"] == ref["charge_to_mass_static"]
    assert got["x_end"] == pytest.approx(ref["x_end"], abs=X_END_TOL)
    assert got["flight_time"] == pytest.approx(ref["flight_time"], abs=FLIGHT_TOL)


def test_ecos_runs_the_package_and_lands_where_the_direct_run_does(fmu_dir, package):
    """ecos reads the connections and the parameter sets (the chute ends at 0.3 m, the shared
    values are both FMUs', charge_to_mass_model and hold_at_end applied), releases the grain
    at the chute's exit with its values and runs the separator to its landing."""
    h = ssp.STEP_SIZE
    got = ecos_run(package, h)
    assert got["chute_length"] == 0.3 and got["time"] == pytest.approx(ssp.STOP_TIME, abs=1e-9)
    values = bound_values(package)
    ref = direct_run(fmu_dir, values["chute"], values["separator"])
    assert got["exit_time"] == ref["exit_time"] and got["charge_to_mass"] == ref["charge_to_mass"]
    assert got["has_released"] and got["ended"]
    assert_lands_as_the_direct_run(got, ref)
    # released at the first communication point after the exit (seen at the end of the step
    # that starts there), ended in the step after release + flight
    release = math.ceil(ref["exit_time"] / h) * h
    assert got["released_seen"] == pytest.approx(release + h, abs=1e-9)
    assert release + got["flight_time"] < got["ended_seen"] <= release + got["flight_time"] + h + 1e-9


# ---- libcosim -----------------------------------------------------------------------------------

def libcosim_run(path, step):
    """The package in libcosim from the .ssp file alone (its first parameter set applied),
    fixed steps of `step` to the default experiment's stop time: (whether simulate_until got
    there, the time reached, libcosim's last error, the separator's outputs)."""
    from libcosimpy._internal import get_last_error_message
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimObserver import CosimObserver

    log_output_level(CosimLogLevel.ERROR)
    execution = CosimExecution.from_ssp_file(str(path), step_size=round(step * 1e9))
    index = {info.name.decode(): info.index for info in execution.slave_infos()}
    assert sorted(index) == ["chute", "separator"]
    vr = {v.name.decode(): v.reference for v in execution.slave_variables(index["separator"])}
    observer = CosimObserver.create_last_value()
    execution.add_observer(observer=observer)
    done = execution.simulate_until(target_time=round(ssp.STOP_TIME * 1e9))
    error = get_last_error_message()
    sep = dict(zip(SEPARATOR_OUTPUTS, observer.last_real_values(index["separator"],
                                                                [vr[n] for n in SEPARATOR_OUTPUTS])))
    sep |= dict(zip(("has_released", "landed"), observer.last_boolean_values(
        index["separator"], [vr["has_released"], vr["landed"]])))
    (sep["bin"],) = observer.last_integer_values(index["separator"], [vr["bin"]])
    return done, execution.status().current_time / 1e9, error, sep


# The package run in libcosim in a process of its own, at libcosim's default log level
# (trace: everything the FMUs log reaches the process's output)
LIBCOSIM_RUN = """
import sys
from libcosimpy.CosimExecution import CosimExecution
path, step, stop = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
execution = CosimExecution.from_ssp_file(path, step_size=step)
assert execution.simulate_until(target_time=stop)
"""


def test_a_libcosim_run_logs_only_what_its_logging_asks_for(package):
    """libcosim turns loggingOn on (the FMI Library does, for its own log level) and asks
    for no category: the FMUs log no trace of its calls. The run printed 9,131 lines, one
    for every call and value set; now the FMI Library's own notes on the descriptions,
    under a hundred lines whatever the length of the run."""
    done = subprocess.run([sys.executable, "-c", LIBCOSIM_RUN, str(package),
                           str(round(ssp.STEP_SIZE * 1e9)), str(round(ssp.STOP_TIME * 1e9))],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]
    lines = (done.stdout + done.stderr).splitlines()
    assert not [line for line in lines if "logFmiCalls" in line]
    assert len(lines) < 100, "\n".join(lines[:20])


def test_libcosim_runs_the_package_to_the_landing(fmu_dir, package):
    """libcosim runs the whole default experiment: the chute's exit and the separator's
    landing complete their steps (hold_at_end), where without it libcosim took the chute's
    fmi2Discard with fmi2Terminated for a failed step ("chute: Step not complete") and ended
    the execution at the exit."""
    done, t, error, sep = libcosim_run(package, ssp.STEP_SIZE)
    assert done, error
    assert t == pytest.approx(ssp.STOP_TIME, abs=1e-9)
    values = bound_values(package)
    ref = direct_run(fmu_dir, values["chute"], values["separator"])
    assert sep["has_released"]
    assert_lands_as_the_direct_run(sep, ref)
