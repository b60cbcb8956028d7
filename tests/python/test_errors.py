"""Invalid calls and values: each is refused with fmi2Error / fmi3Error and a message,
through the importer's logger, naming the variable, the value and the valid range; the
instance stays usable. Log categories do what they say. Unsupported functions refuse
with a reason instead of crashing."""

import ctypes
import inspect
import math
import types
import typing

import pytest

from tribo_fmu import ERROR, OK, VERSIONS, Slave, core_run, status_of

SMALL = {"n_segments": 64}


def fresh(fmu_dir, version, **kwargs):
    return Slave(fmu_dir(version), version, **kwargs)


def run_to_one(s, output_names):
    """Finish initialization if needed and run to t = 1: what an undisturbed run gives."""
    return s.run([0.5, 1.0], output_names)[-1]


def undisturbed(fmu_dir, version, output_names):
    return run_to_one(fresh(fmu_dir, version).init(**SMALL), output_names)


# (variable, refused value, words the message must contain: the variable, the value, the range)
INVALID_VALUES = [
    ("epsilon", 1.5, ["epsilon = 1.5", "0.001 <= epsilon <= 1"]),
    ("epsilon", 0.0, ["epsilon = 0", "0.001 <= epsilon <= 1"]),
    ("mu", math.nan, ["mu = nan", "0 <= mu <= 100"]),
    ("Gamma", math.inf, ["Gamma = inf", "1e-12 <= Gamma <= 10"]),
    ("beta", -math.inf, ["beta = -inf", "0 <= beta < 1.5708"]),  # rad
    ("beta", math.pi / 2, ["beta = 1.5707963267948966", "0 <= beta < 1.5708"]),
    ("dt", 0.5, ["dt = 0.5", "1e-09 <= dt <= 0.1"]),
    ("n_segments", 8, ["n_segments = 8", "16 <= n_segments <= 100000"]),
    ("charge_model_static", 2, ["charge_model_static = 2", "0 <= charge_model_static <= 1"]),
    ("integrator", -1, ["integrator = -1", "integrator <="]),
    ("damping_point", 2, ["damping_point = 2", "0 <= damping_point <= 1"]),
    ("work_limit", 0, ["work_limit = 0", "1 <= work_limit <= 2147483647"]),
    ("F_T_ext", math.nan, ["F_T_ext = nan", "-10 <= F_T_ext <= 10"]),
    ("F_N_ext", math.inf, ["F_N_ext = inf", "-10 <= F_N_ext <= 10"]),
    ("F_N_ext", -1e12, ["F_N_ext = -1000000000000", "-10 <= F_N_ext <= 10"]),
]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("name, value, words", INVALID_VALUES,
                         ids=[f"{n}={v}" for n, v, _ in INVALID_VALUES])
def test_invalid_values_are_refused_and_explained(fmu_dir, output_names, version, name, value,
                                                  words):
    s = fresh(fmu_dir, version)
    before = s.get(name)
    assert status_of(s.set, **{name: value}) == ERROR
    message = s.errors()[-1]
    assert all(w in message for w in words), message
    assert s.get(name) == before
    assert run_to_one(s.init(**SMALL), output_names) == undisturbed(fmu_dir, version, output_names)


@pytest.mark.parametrize("version", VERSIONS)
def test_tunables_are_checked_in_step_mode_too(fmu_dir, output_names, version):
    s = fresh(fmu_dir, version).init(**SMALL)
    s.step_to(0.5)
    assert status_of(s.set, mu=-0.1) == ERROR
    assert "mu = -0.10000000000000001" in s.errors()[-1] and "0 <= mu <= 100" in s.errors()[-1]
    assert status_of(s.set, tau0=math.nan) == ERROR
    assert "tau0 = nan" in s.errors()[-1] and "0 <= tau0 <= 1e+09" in s.errors()[-1]
    assert s.get("mu") == 0.1
    assert s.run([1.0], output_names)[-1] == undisturbed(fmu_dir, version, output_names)


@pytest.mark.parametrize("version", VERSIONS)
def test_calls_in_the_wrong_state_are_refused(fmu_dir, output_names, version):
    s = fresh(fmu_dir, version)
    assert status_of(s.fmu.doStep, 0.0, 0.1) == ERROR
    assert "not allowed in state Instantiated" in s.errors()[-1]
    assert status_of(s.get, "X") == ERROR  # outputs exist from initialization on
    assert "X" in s.errors()[-1] and "Instantiated" in s.errors()[-1]
    assert status_of(s.fmu.exitInitializationMode) == ERROR
    assert status_of(s.fmu.terminate) == ERROR
    s.init(**SMALL)
    if version == 2:
        assert status_of(s.fmu.setupExperiment, startTime=0.0) == ERROR
    assert status_of(s.fmu.enterInitializationMode) == ERROR
    s.step_to(0.5)
    s.fmu.terminate()
    assert status_of(s.fmu.doStep, 0.5, 0.5) == ERROR
    assert "Terminated" in s.errors()[-1]
    assert status_of(s.set, mu=0.2) == ERROR  # tunable, but the run is over
    assert "mu = 0.2" in s.errors()[-1] and "Terminated" in s.errors()[-1]
    assert s.get("X") == fresh(fmu_dir, version).init(**SMALL).run([0.5], ["X"])[-1]["X"]
    s.reset()  # and a reset brings it back
    assert run_to_one(s.init(**SMALL), output_names) == undisturbed(fmu_dir, version, output_names)


@pytest.mark.parametrize("version", VERSIONS)
def test_wrong_value_references_and_types_are_refused(fmu_dir, output_names, version):
    s = fresh(fmu_dir, version).init(**SMALL)
    real = s.fmu.getReal if version == 2 else s.fmu.getFloat64
    set_real = s.fmu.setReal if version == 2 else s.fmu.setFloat64
    set_integer = s.fmu.setInteger if version == 2 else s.fmu.setInt32
    assert status_of(real, [999]) == ERROR
    assert "unknown value reference 999" in s.errors()[-1]
    if version == 2:  # the FMI 3.0 arrays do not exist in FMI 2.0
        assert status_of(real, [301]) == ERROR
        assert "unknown value reference 301" in s.errors()[-1]
    n_segments = s.variables["n_segments"].valueReference
    assert status_of(set_real, [n_segments], [32.0]) == ERROR
    assert "n_segments" in s.errors()[-1] and "type" in s.errors()[-1]
    x = s.variables["X"].valueReference
    assert status_of(set_real, [x], [0.5]) == ERROR
    assert "X" in s.errors()[-1] and "output" in s.errors()[-1] and "0.5" in s.errors()[-1]
    assert status_of(set_real, [0], [3.0]) == ERROR
    assert "time" in s.errors()[-1] and "independent" in s.errors()[-1]
    # the removed charge_model (an Enumeration: an Integer in FMI 2.0, an Int64 in 3.0)
    set_enumeration = s.fmu.setInteger if version == 2 else s.fmu.setInt64
    assert status_of(set_enumeration, [17], [3]) == ERROR
    assert ("value reference 17 is retired (it was charge_model's): charge_model was removed: "
            "select the charge models with their switches charge_model_<name>") in s.errors()[-1]
    assert status_of(set_integer, [x], [1]) == ERROR
    assert run_to_one(s, output_names) == undisturbed(fmu_dir, version, output_names)


def test_fmi3_value_counts_must_match(fmu_dir):
    s = fresh(fmu_dir, 3).init(**SMALL)
    static = s.variables["segment_charge_static"].valueReference
    x = s.variables["X"].valueReference
    assert status_of(s.fmu.getFloat64, [static, x], nValues=64) == ERROR
    assert "nValues = 64" in s.errors()[-1] and "65 values" in s.errors()[-1]
    assert len(s.fmu.getFloat64([static, x], nValues=65)) == 65
    assert status_of(s.fmu.getFloat32, [x]) == ERROR
    assert "X" in s.errors()[-1] and "Float64" in s.errors()[-1]


@pytest.mark.parametrize("present, absent", [("static", "sliding"), ("sliding", "static")])
def test_fmi3_array_of_a_model_left_out_reads_zeros(fmu_dir, reference_exe, present, absent):
    """Documented choice: like Q_static / Q_sliding, a charge model the scene leaves out
    reads as zero charge, so an importer recording every output is not refused."""
    off = {f"charge_model_{absent}": 0}
    s = fresh(fmu_dir, 3).init(**off, **SMALL)
    s.step_to(1.0)
    core = core_run(reference_exe, dict(SMALL, **off), [(1.0, [])],
                    segments=True)[0]["segments"]
    assert s.get(f"segment_charge_{present}") == core[present] and max(core[present]) > 0
    assert core[absent] is None and s.get(f"segment_charge_{absent}") == [0.0] * 64


# ---- logging -------------------------------------------------------------------------

def call_messages(s):
    return [m for _, c, m in s.messages if c == "logFmiCalls"]


@pytest.mark.parametrize("version", VERSIONS)
def test_log_categories_are_honoured(fmu_dir, version):
    s = fresh(fmu_dir, version).init(**SMALL)
    s.step_to(0.25)
    assert call_messages(s) == []  # debug logging is off by default...
    assert status_of(s.set, epsilon=2.0) == ERROR
    assert len(s.errors()) == 1  # ...but errors are reported

    s.fmu.setDebugLogging(True, ["logFmiCalls"])
    s.step_to(0.5)
    assert any("DoStep" in m and "0.25" in m for m in call_messages(s))
    s.fmu.setDebugLogging(False, ["logFmiCalls"])
    count = len(call_messages(s))
    s.step_to(0.75)
    assert len(call_messages(s)) == count

    s.fmu.setDebugLogging(False, ["logStatusError"])
    assert status_of(s.set, epsilon=2.0) == ERROR  # still refused, silently
    assert len(s.errors()) == 1
    s.fmu.setDebugLogging(True, [])  # every category
    s.step_to(1.0)
    assert status_of(s.set, epsilon=2.0) == ERROR
    assert len(s.errors()) == 2 and len(call_messages(s)) > count


@pytest.mark.parametrize("version", VERSIONS)
def test_logging_on_at_instantiation_leaves_the_call_trace_off(fmu_dir, version):
    """loggingOn, which an importer may turn on for its own log level (libcosim through the
    FMI Library), does not trace every call: only SetDebugLogging asking for logFmiCalls,
    by name or with every category, does."""
    s = fresh(fmu_dir, version, logging_on=True).init(**SMALL)
    s.step_to(0.5)
    assert call_messages(s) == []
    s.fmu.setDebugLogging(True, [])
    s.step_to(1.0)
    assert any(m.startswith(f"fmi{version}DoStep") for m in call_messages(s))


@pytest.mark.parametrize("version", VERSIONS)
def test_unknown_log_category_is_refused(fmu_dir, version):
    s = fresh(fmu_dir, version)
    assert status_of(s.fmu.setDebugLogging, True, ["logFmiCalls", "logEverything"]) == ERROR
    assert "unknown log category 'logEverything'" in s.errors()[-1]
    s.init(**SMALL)
    s.step_to(0.5)
    assert call_messages(s) == []  # nothing was changed by the refused call
    # a '%' survives FMI 2.0's printf-style logger
    assert status_of(s.fmu.setDebugLogging, True, ["100%"]) == ERROR
    assert "'100%'" in s.errors()[-1]


# ---- functions behind capabilities this FMU does not have --------------------------------

REFUSED = {
    2: ["fmi2GetDirectionalDerivative", "fmi2EnterEventMode", "fmi2NewDiscreteStates",
        "fmi2EnterContinuousTimeMode", "fmi2CompletedIntegratorStep", "fmi2SetTime",
        "fmi2SetContinuousStates", "fmi2GetDerivatives", "fmi2GetEventIndicators",
        "fmi2GetContinuousStates", "fmi2GetNominalsOfContinuousStates",
        "fmi2SetRealInputDerivatives", "fmi2GetRealOutputDerivatives", "fmi2CancelStep",
        "fmi2GetStatus", "fmi2GetRealStatus", "fmi2GetIntegerStatus", "fmi2GetBooleanStatus",
        "fmi2GetStringStatus"],
    3: ["fmi3EnterEventMode", "fmi3GetNumberOfVariableDependencies", "fmi3GetVariableDependencies",
        "fmi3GetDirectionalDerivative", "fmi3GetAdjointDerivative", "fmi3GetIntervalDecimal",
        "fmi3GetIntervalFraction", "fmi3GetShiftDecimal", "fmi3GetShiftFraction",
        "fmi3SetIntervalDecimal", "fmi3SetIntervalFraction", "fmi3SetShiftDecimal",
        "fmi3SetShiftFraction", "fmi3EvaluateDiscreteStates", "fmi3UpdateDiscreteStates",
        "fmi3EnterContinuousTimeMode", "fmi3CompletedIntegratorStep", "fmi3SetTime",
        "fmi3SetContinuousStates", "fmi3GetContinuousStateDerivatives", "fmi3GetEventIndicators",
        "fmi3GetContinuousStates", "fmi3GetNominalsOfContinuousStates",
        "fmi3GetNumberOfEventIndicators", "fmi3GetNumberOfContinuousStates", "fmi3EnterStepMode",
        "fmi3GetOutputDerivatives", "fmi3ActivateModelPartition"],
}


def c_function(fmu, name):
    """The FMI function from the FMU's library, typed as fmpy declares it (fmpy's
    co-simulation class leaves out the model-exchange functions of FMI 2.0)."""
    if name in fmu._functions:
        return fmu._functions[name]
    from fmpy.fmi2 import FMU2Model
    parameters = list(inspect.signature(getattr(FMU2Model, name)).parameters.values())[1:]
    f = getattr(fmu.dll, name)
    f.argtypes = [typing.get_args(p.annotation)[0] if isinstance(p.annotation, types.UnionType)
                  else p.annotation for p in parameters]
    f.restype = ctypes.c_int
    return f


def null_arguments(function, component):
    """component, then a zero or NULL of the right C type for every other argument."""
    args = [component]
    for t in function.argtypes[1:]:
        if t in (ctypes.c_double, ctypes.c_float):
            args.append(0.0)
        elif t in (ctypes.c_bool,):
            args.append(False)
        elif issubclass(t, (ctypes._Pointer, ctypes.c_void_p, ctypes.c_char_p)) or \
                getattr(t, "_flags_", 0) & ctypes._FUNCFLAG_CDECL:
            args.append(None)
        else:
            args.append(0)
    return args


@pytest.mark.parametrize("version", VERSIONS)
def test_unsupported_functions_refuse_with_a_reason(fmu_dir, version):
    s = fresh(fmu_dir, version).init(**SMALL)
    for name in REFUSED[version]:
        f = c_function(s.fmu, name)
        count = len(s.errors())
        assert f(*null_arguments(f, s.fmu.component)) == ERROR, name
        assert len(s.errors()) == count + 1 and s.errors()[-1].startswith(name), name
    s.step_to(0.5)  # none of them harmed the instance
    assert s.get("time") == 0.5


def test_fmi2_status_inquiries_that_make_sense_are_answered(fmu_dir):
    from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated
    s = fresh(fmu_dir, 2).init(**SMALL)
    s.step_to(0.5)
    assert s.fmu.getRealStatus(fmi2LastSuccessfulTime) == 0.5
    assert s.fmu.getBooleanStatus(fmi2Terminated) is False


@pytest.mark.parametrize("version", VERSIONS)
def test_other_interface_types_are_refused_at_instantiation(fmu_dir, version):
    s = fresh(fmu_dir, version)
    guid = s.md.guid.encode()
    if version == 2:
        f = s.fmu._functions["fmi2Instantiate"]
        assert not f(b"me", 0, guid, b"", ctypes.byref(s._callbacks), 0, 0)  # fmi2ModelExchange
        assert not f(b"wrong_guid", 1, b"{0}", b"", ctypes.byref(s._callbacks), 0, 0)
        assert not f(b"", 1, guid, b"", ctypes.byref(s._callbacks), 0, 0)
    else:
        me = s.fmu._functions["fmi3InstantiateModelExchange"]
        assert not me(b"me", guid, b"", False, False, None, s.fmu.logMessage)
        cs = s.fmu._functions["fmi3InstantiateCoSimulation"]
        assert not cs(b"events", guid, b"", False, False, True, False, None, 0, None,
                      s.fmu.logMessage, s.fmu.intermediateUpdate)
        assert not cs(b"wrong_token", b"{0}", b"", False, False, False, False, None, 0, None,
                      s.fmu.logMessage, s.fmu.intermediateUpdate)
    errors = s.errors()
    assert any("co-simulation only" in m for m in errors)
    assert any("token" in m for m in errors)
    assert status_of(s.fmu.doStep, 0.0, 0.1) == ERROR  # the first instance is unaffected
    assert OK == status_of(s.init, **SMALL)
