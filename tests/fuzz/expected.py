"""The model of what a tribo FMU answers, for the fuzz suite: the status each call must
return (the FMI standard's state machines, and fmu/README.md: a refused call changes
nothing and the instance stays usable) and the state it leaves the instance in.

Where the FMU may choose, the model accepts each choice it may make: a step that spends
the work limit ends early (Discard, or an early return where allowed), and one in which the
particle leaves the chute ends the run there (Discard with fmi2Terminated; FMI 3.0 OK with
terminateSimulation). After such a step the model knows the core's time only as far as the
FMU's time resolves it, and accepts either answer to a step whose end lies that close to it.

The time (fmu/README.md): a communication point is the FMU's time up to rounding, a step
must end after the FMU's time and move the model's time (the FMU's less the start time, in
the model's unit), and the time a step reaches is never before the FMU's time, and before
the step's end where it ended early."""

import copy
import math
import os
import xml.etree.ElementTree as ET

from fmi_calls import DISCARD, ERROR, OK, function_type
from front_ends import front_end_of, rigid_stick_valid

INSTANTIATED = "Instantiated"
CONFIGURATION = "Configuration Mode"
INITIALIZATION = "Initialization Mode"
STEP = "Step Mode"
DISCARDED = "Step Discarded"  # FMI 2.0's stepFailed
TERMINATED = "Terminated"
FAILED = "failed"
EXITED = "Exited"  # the core's run is over (the chute's exit, the separator's bins or plate)

EITHER = "either"  # expect_step: the model cannot tell whether the step is refused

READABLE = {INITIALIZATION, STEP, DISCARDED, TERMINATED, FAILED, EXITED}  # outputs from here on
TIME_MAX = 1e12  # beyond it the core refuses (src/chute/tribo.h)


def rounding_tolerance(t):
    return 1e-9 * max(1.0, abs(t))


def declared(fmu_dir):
    """Each variable's min, max and start by value reference, from the XML itself (fmpy
    leaves out those of some types, e.g. UInt64)."""
    root = ET.parse(os.path.join(fmu_dir, "modelDescription.xml")).getroot()
    out = {}
    for element in root.find("ModelVariables"):
        attributes = dict(element.attrib)
        if root.get("fmiVersion", "").startswith("2"):
            attributes.update(element[0].attrib)  # FMI 2.0: on the type's element
        out[int(attributes["valueReference"])] = attributes
    return out


class Variable:
    def __init__(self, v, version, attributes):
        self.name, self.vr, self.type = v.name, v.valueReference, v.type
        self.causality, self.variability = v.causality, v.variability
        self.ftype = function_type(version, v.type)
        self.is_integer = v.type not in ("Real", "Float64", "Float32")
        self.min = float(attributes.get("min", -math.inf))
        self.max = float(attributes.get("max", math.inf))
        start = attributes.get("start", "0")
        self.start = float({"false": "0", "true": "1"}.get(start, start))  # a Boolean's
        self.dimension = v.dimensions[0].valueReference if v.dimensions else None
        # a real parameter without a max takes the infinity too (chute_length: no end)
        self.takes_infinity = not self.is_integer and "max" not in attributes and \
            self.causality == "parameter"

    @property
    def settable(self):
        return self.causality in ("parameter", "structuralParameter", "input")

    def valid(self, value):
        if self.type == "Boolean":  # fmi2True or fmi2False (FMI 3.0's C bool is one of them)
            return value in (0.0, 1.0)
        if value == math.inf and self.takes_infinity:
            return True
        if not math.isfinite(value) or not (self.min <= value <= self.max):
            return False
        return not self.is_integer or value == math.floor(value)


class Model:
    def __init__(self, md, fmu_dir, version, early_return):
        self.version = version
        self.early_return = early_return
        attributes = declared(fmu_dir)
        self.variables = [Variable(v, version, attributes[v.valueReference])
                          for v in md.modelVariables]
        self.by_vr = {v.vr: v for v in self.variables}
        # the dimensionless model's variables, the SI front end's or the separator's
        # (front_ends.py)
        self.front = front_end_of(md.coSimulation.modelIdentifier)
        self.reset()

    def reset(self):
        self.lifecycle = INSTANTIATED
        self.values = {v.name: v.start for v in self.variables if v.settable}
        self.start, self.stop, self.time, self.core_time = 0.0, None, 0.0, 0.0
        # the core's time is core_time exactly, or (after a step that ended early) only up to
        # the resolution of the FMU's time
        self.core_time_exact = True
        # rtol, atol set by the importer: the experiment's tolerance leaves them
        self.explicit = set()

    def copy(self):
        other = copy.copy(self)
        other.values = dict(self.values)
        other.explicit = set(self.explicit)
        return other

    # ---- values ------------------------------------------------------------------------

    def scene_valid(self):
        """Whether the parameters, each valid, also go together (the core's combinations:
        the drop lies on the chute; the SI FMU's: what they derive is in the model's
        ranges). Otherwise the model cannot be made: initialization and the outputs are
        refused."""
        return self.front.scene_valid(self.values)

    def time_scale(self):
        """The FMU's unit of time per unit of the model's: the fuzz suite's steps are sized in
        the model's units (an SI FMU's second is ~10^6 of them)."""
        return self.front.time_unit(self.values)

    def initialization_valid(self):
        """Whether initialization ends: the scene makes a model and it takes the inputs."""
        return self.scene_valid() and self.front.inputs_valid(self.values)

    def count(self, v):
        return int(self.values[self.by_vr[v.dimension].name]) if v.dimension is not None else 1

    def _settable_now(self, v):
        if self.version == 3 and v.causality == "structuralParameter":
            return self.lifecycle in (INSTANTIATED, CONFIGURATION)
        states = {INSTANTIATED, INITIALIZATION}
        if v.variability == "tunable" or v.causality == "input":
            states.add(STEP)
        return self.lifecycle in states

    def _resolved(self, ftype, vrs, n_values):
        """The variables of a call, or None if one is unknown, of another type, or the
        values do not fit."""
        variables = [self.by_vr.get(vr) for vr in vrs]
        if any(v is None or v.ftype != ftype for v in variables):
            return None
        if sum(self.count(v) for v in variables) != n_values:
            return None
        return variables

    def expect_get(self, ftype, vrs, n_values):
        """The statuses a get may return."""
        variables = self._resolved(ftype, vrs, n_values)
        if variables is None:
            return {ERROR}
        # outputs and calculated parameters are computed from Initialization Mode on
        if any(v.causality in ("output", "calculatedParameter") for v in variables):
            if self.lifecycle not in READABLE:
                return {ERROR}
            if self.lifecycle == INITIALIZATION and not self.scene_valid():
                return {ERROR}
            if self.lifecycle == FAILED:  # an output the failure left not finite is refused
                return {OK, ERROR}
        return {OK}

    def expect_set(self, ftype, vrs, values):
        """The status of a set, and the new values if it applies (all of them, or none)."""
        variables = self._resolved(ftype, vrs, len(values))
        if variables is None:
            return ERROR, None
        for v, value in zip(variables, values):
            if not v.settable or not v.valid(float(value)) or not self._settable_now(v):
                return ERROR, None
            # the running model must take it too (the SI front end's conversion)
            if self.lifecycle == STEP and \
                    not self.front.accepts_while_running(v.name, float(value), self.values):
                return ERROR, None
        # the rigid stick chosen explicitly with the fixed step or the centre's dashpot is
        # refused at the set call that makes the conflict
        trial, explicit = dict(self.values), set(self.explicit)
        for v, value in zip(variables, values):
            trial[v.name] = float(value)
            explicit |= {v.name} & {"stick_model"}
        self._follow(trial, explicit)
        if "stick_model" in trial and not rigid_stick_valid(trial):
            return ERROR, None
        return OK, list(zip(variables, values))

    def _follow(self, values, explicit):
        """stick_model, where not set explicitly, follows the integrator and the dashpot's
        point: its start value, the rigid stick only where they allow it."""
        if "stick_model" not in values or "stick_model" in explicit:
            return
        start = next(v.start for v in self.variables if v.name == "stick_model")
        values["stick_model"] = start
        if not rigid_stick_valid(values):
            values["stick_model"] = 0.0

    def apply(self, assignments):
        for v, value in assignments:
            self.values[v.name] = float(value)
            if v.name in ("rtol", "atol", "stick_model"):
                self.explicit.add(v.name)
        self._follow(self.values, self.explicit)

    # ---- the life cycle ------------------------------------------------------------------

    def _tolerances(self, tolerance):
        """rtol and atol of an experiment's tolerance: atol keeps the defaults' ratio."""
        rtol, atol = (next(v for v in self.variables if v.name == n) for n in ("rtol", "atol"))
        return (rtol, tolerance), (atol, atol.start * (tolerance / rtol.start))

    def experiment_valid(self, start, stop, tolerance=None):
        """Whether the experiment is taken: a start and stop time, and a tolerance that gives
        rtol and atol in their ranges (even where both were set, which it does not change)."""
        if tolerance is not None and not all(v.valid(x) for v, x in self._tolerances(tolerance)):
            return False
        return math.isfinite(start) and (stop is None or (math.isfinite(stop) and stop >= start))

    def set_experiment(self, start, stop, tolerance=None):
        self.start, self.stop, self.time, self.core_time = start, stop, start, 0.0
        self.core_time_exact = True
        if tolerance is not None:
            for v, x in self._tolerances(tolerance):
                if v.name not in self.explicit:
                    self.values[v.name] = x

    def rounding_tolerance(self):
        return rounding_tolerance(self.time)

    def expect_step(self, current, h):
        """ERROR for a step the FMU must refuse, None if it computes (OK, or it ends early),
        EITHER where the model cannot tell (the step's end lies within the resolution of the
        FMU's time of the core's time, which the model knows only that far)."""
        if self.lifecycle != STEP:
            return ERROR
        if not math.isfinite(current) or abs(current - self.time) > rounding_tolerance(self.time):
            return ERROR
        if not (math.isfinite(h) and h > 0.0):
            return ERROR
        end = current + h
        if not (math.isfinite(end) and end > current):
            return ERROR
        if not end > self.time:  # the time never goes back
            return ERROR
        if self.stop is not None and end > self.stop + rounding_tolerance(self.stop):
            return ERROR
        unit = self.front.time_unit(self.values)
        core_end = (end - self.start) / unit
        if core_end > TIME_MAX:
            return ERROR
        if not self.front.resolves(core_end, self.values):
            return ERROR
        # the step must move the model's time
        if self.core_time_exact:
            return None if core_end > self.core_time else ERROR
        resolution = 2.0 * math.ulp(max(abs(self.time), abs(self.start))) / unit
        if core_end <= self.core_time - resolution:
            return ERROR
        return EITHER if core_end <= self.core_time + resolution else None

    def step_allowed(self, status, early, current, h, reached, terminate=False):
        """Whether a computed step's answer is one the FMU may give; updates the model. A
        failure of the core is one (an error, with its reason logged): the instance then
        only resets or restores a state. So is the end of the run, where the particle leaves
        the chute: FMI 2.0 Discard, FMI 3.0 OK with an early return where allowed, at the
        exit time."""
        end = current + h
        unit = self.front.time_unit(self.values)
        if status == ERROR:
            self.lifecycle = FAILED
            return True
        if terminate:
            if (status, early) != ((DISCARD, False) if self.version == 2 else (OK, self.early_return)):
                return False
            if not (self.time <= reached <= end):
                return False
            self.time = reached
            self.core_time, self.core_time_exact = (reached - self.start) / unit, False
            self.lifecycle = EXITED
            return True
        if status == OK and not early:
            if reached != end:
                return False
            self.time = end
            self.core_time, self.core_time_exact = (end - self.start) / unit, True
            return True
        ended_early = (status == OK and early and self.early_return) or \
            (status == DISCARD and not early)
        # at the time reached: not before the FMU's time (the importer's point may lie a
        # rounding before it), before the step's end (the importer's, which its point may
        # pass by a rounding: the core then integrates to it, as FMI 2.0's 4.2.2 suggests)
        if not ended_early or not (self.time <= reached < end):
            return False
        self.time = reached
        self.core_time, self.core_time_exact = (reached - self.start) / unit, False
        if status == DISCARD and self.version == 2:
            self.lifecycle = DISCARDED
        return True
