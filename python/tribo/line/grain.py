"""One grain through the separation line: down the SI chute (tribo_si_fmi<v>) to its exit,
then through the free-fall separator (tribo_separator_fmi<v>) from the chute's exit state,
at one or several electrode voltages (docs/line.md, docs/separator.md "Coupling").

The chute runs as a population's particle does (populations.feed.run_particle: the same
parameters, one step to the horizon, so its row is a population's row); its run ends
at the exit exactly (the FMU ends the step there), at the time `time_end`. The separator is
then initialised with the grain and the chute's tilt bound to the chute's values, stepped
(holding the grain) to that exit time, given the chute's outputs there as its inputs
(exited -> released, u -> u_entry, v -> v_entry, charge_to_mass -> charge_to_mass) and
stepped in one step to the separator's horizon: the FMU ends that step where the grain
reaches the bins or a plate, located exactly. The chute's part does not depend on the
separator's settings: a voltage sweep runs it once per grain and the separator once per
voltage.

The chute runs with ONE charge model (`charge_model`, a name of the SI FMU's registered
models, fmu/charge_models.py; "static" by default), the one its output `charge_to_mass`
carries (`charge_to_mass_model`): the charge models are alternative laws of the same
grain's charge (docs/model.md section 5), and the others' work would be spent for nothing.
The static model is the default because it is the one the populations' results are read
with (docs/populations.md); any other registered model may be chosen.
"""

import hashlib
import json
import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..batch.particle import RunResult
from ..batch.specs import RunSpec
from ..fmu import FmuImage, Instance
from ..fmu.instance import Rows, Values
from ..fmu.charge_models import charge_models, switches
from ..fmu.locate import find_fmu
from ..fmu.names import format_number, to_fmu
from ..fmu.parameters import check_values
from ..fmu.reuse import Instances, instance_for, shares_instances
from ..populations.feed import result_columns as chute_columns
from ..populations.feed import run_particle

# the separator's parameters the chute's grain and scene bind, by the package's names
SHARED = ("size", "epsilon", "density", "tilt_deg", "gravity")
# the separator's settings a line may give, by the package's names (docs/separator.md)
SEPARATOR_SETTINGS = ("gap", "height", "n_bins", "x_entry", "chute_direction", "air_density",
                      "air_viscosity", "rtol", "atol", "work_limit")
# the separator's horizon after the release, s: a grain still falling then is "airborne"
SEPARATOR_HORIZON = 10.0
# per grain and voltage (docs/separator.md, "Outputs"); `landed` 1 at the bins, `electrode`
# -1 / +1 on a plate, both 0: not ended within the horizon (airborne) or not released
# (the grain did not leave the chute)
LANDING_COLUMNS = ["landed", "electrode", "bin", "x_end", "z_end", "flight_time", "time_land"]
INTEGER_LANDING_COLUMNS = ("landed", "electrode", "bin")
# per grain, whatever the voltage
GRAIN_COLUMNS = ["charge_to_mass", "q_per_m", "mass", "equivalent_diameter"]
OUTPUTS = ["landed", "electrode", "bin", "x_end", "z_end", "flight_time", "q_per_m", "mass",
           "equivalent_diameter"]
# the separator's inputs at the release, in the order fly sets them
INPUTS = ("u_entry", "v_entry", "charge_to_mass")


class LineError(ValueError):
    """A line that cannot be run as given (the message, one line, names the value)."""


def charge_model_settings(charge_model: str, models) -> dict:
    """The chute's switches that leave one charge model of `models` (the SI FMU's, in the
    registry's order) on, and its charge_to_mass_model (the registry's row, from 1)."""
    if charge_model not in models:
        raise LineError(f"charge_model = {charge_model!r}: one of {', '.join(models)}")
    return {switch: int(m == charge_model) for m, switch in zip(models, switches(models))} | \
        {"charge_to_mass_model": models.index(charge_model) + 1}


def the_charge_model(params: dict, models) -> str:
    """The one model a grain's chute parameters leave on (charge_model_settings)."""
    return next(m for m, switch in zip(models, switches(models)) if params.get(switch, 1))


@dataclass(frozen=True)
class LineImages:
    """What every grain's task needs besides its chute parameters: both FMUs' bytes, the
    separator's settings and the voltages. `sha256` identifies them all (a grain's key is
    its chute run's and this), so a results folder's rows are of this line."""

    chute: FmuImage
    separator: FmuImage
    settings: dict = field(hash=False)  # the separator's, by the package's names
    voltages: tuple = ()
    horizon: float = SEPARATOR_HORIZON

    @property
    def name(self) -> str:
        return f"{self.chute.name} + {self.separator.name}"

    @property
    def models(self) -> tuple:
        """The chute's charge models (fmu/charge_models.py)."""
        return charge_models(self.chute.model_description())

    @property
    def sha256(self) -> str:
        text = json.dumps({"chute": self.chute.sha256, "separator": self.separator.sha256,
                           "settings": self.settings, "voltages": list(self.voltages),
                           "horizon": self.horizon}, sort_keys=True)
        return hashlib.sha256(text.encode()).hexdigest()


def check_separator(separator: FmuImage, settings: dict, voltages, sizes=()) -> None:
    """LineError / ParameterError, one line, for a setting or voltage the separator refuses,
    or a grain that does not fit the gap (checked here, before any run)."""
    unknown = [n for n in settings if n not in SEPARATOR_SETTINGS]
    if unknown:
        raise LineError(f"not a separator setting: {unknown[0]} (they are: "
                        f"{', '.join(SEPARATOR_SETTINGS)})")
    if not len(voltages):
        raise LineError("no voltage given")
    values = {name: [value] for name, value in settings.items()}
    values["voltage"] = list(voltages)
    check_values(separator, values)
    md = separator.model_description()
    gap = settings.get("gap", _start(md, "gap"))
    x_entry = abs(settings.get("x_entry", 0.0))
    largest = max(sizes, default=0.0)
    if largest and largest / 2 + x_entry >= gap / 2:
        raise LineError(f"size = {format_number(float(largest))} m does not fit the gap = "
                        f"{format_number(float(gap))} m at x_entry = "
                        f"{format_number(float(settings.get('x_entry', 0.0)))} m: the grain must "
                        f"satisfy size/2 + |x_entry| < gap/2")


def _start(md, name):
    return next(float(v.start) for v in md.modelVariables if v.name == name)


def separator_parameters(chute_params: dict, settings: dict, voltage: float) -> dict:
    """The separator's parameters (the package's names): the grain and tilt bound to the
    chute's values, the settings, the voltage."""
    bound = {name: chute_params[name] for name in SHARED if name in chute_params}
    return {**bound, **settings, "voltage": float(voltage)}


def fly(separator: FmuImage, fmu_params: dict, t_exit: float, inputs: dict | None,
        horizon: float = SEPARATOR_HORIZON) -> dict:
    """One separator run: initialised with `fmu_params` (the FMU's names and units:
    fmu.names.to_fmu), the grain held until t_exit, then released with `inputs` (u_entry,
    v_entry, charge_to_mass; None: never released) and stepped in one step to t_exit + horizon
    (the FMU ends the step where the run ends). Returns OUTPUTS and time_land (the time the
    run ended, NaN if it did not)."""
    s = Instance(separator, name="separator")
    try:
        s.init(0.0, None, **fmu_params)
        if t_exit > 0:
            s.step_to(t_exit)
        if inputs is not None:
            s.set(released=True, **inputs)
            s.step_to(t_exit + horizon)
        out = s.get_many(OUTPUTS)
        out["time_land"] = s.t if s.get("ended") else math.nan
        s.terminate()
    finally:
        s.free()
    out["landed"] = int(out["landed"])
    out["electrode"] = int(out["electrode"])
    out["bin"] = int(out["bin"])
    return out


class Flights:
    """One grain's flights (fly's, to the bit: tests/python/test_line.py) on one separator
    instance: before each flight but the first the instance is reset (fmi3Reset /
    fmi2Reset: the FMU frees its core and restores every start value, the state a new
    instance has), its parameters `names` and the inputs at the release are set by value
    reference (fmu/instance.py's Values: one FMI call per type, in fly's order) and its
    outputs read in one call per type (Rows): an instance made and freed, values set and
    read by name one by one, cost fly more CPU than the separator's core spends on the
    flight (docs/line.md, "Benchmark: the line against its core")."""

    def __init__(self, separator: FmuImage, names, horizon: float = SEPARATOR_HORIZON,
                 instance: Instance | None = None):
        # `instance`: one in the state a new one has, that the caller frees (a task's kept
        # instance, fmu/reuse.py); else one of the flights' own, freed on leaving
        self.horizon = horizon
        self.own = instance is None
        self.instance = Instance(separator, name="separator") if self.own else instance
        try:
            self.parameters = Values(self.instance, names)
            self.release = Values(self.instance, ("released",) + INPUTS)
            self.outputs = Rows(self.instance, OUTPUTS + ["ended"], capacity=1)
        except BaseException:
            if self.own:
                self.instance.free()
            raise
        self.flown = False

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        if self.own:
            self.instance.free()
        return False

    def fly(self, values, t_exit: float, inputs) -> dict:
        """fly's flight: the parameters' `values` (in the order of the names), the grain
        held until t_exit, then released with `inputs` (INPUTS' values; None: never
        released) and stepped in one step to t_exit + horizon. Returns fly's dict."""
        s = self.instance
        if self.flown:
            s.reset()
        self.flown = True
        self.parameters.set(values)
        s.initialize(0.0, None)
        if t_exit > 0:
            s.step_to(t_exit)
        if inputs is not None:
            self.release.set((True,) + tuple(inputs))
            s.step_to(t_exit + self.horizon)
        self.outputs.clear()
        self.outputs.read()
        values = self.outputs.table()[0].tolist()  # Python floats, as fmpy's getters give
        out = dict(zip(OUTPUTS, values))
        out["time_land"] = s.t if values[-1] else math.nan
        for c in INTEGER_LANDING_COLUMNS:
            out[c] = int(out[c])
        return out


# a grain's parameters that are not the chute FMU's: its material's name, its entry point
# across the separator's gap (m)
LINE_PARAMETERS = ("particle", "x_entry")


def chute_params_of(params: dict) -> dict:
    """A spec's parameters less what is not the chute FMU's (LINE_PARAMETERS)."""
    return {k: v for k, v in params.items() if k not in LINE_PARAMETERS}


@shares_instances
def run_line_grain(images: LineImages, spec: RunSpec,
                   instances: Instances | None = None) -> RunResult:
    """One grain: the chute once (its row: populations.feed.result_columns), then the
    separator at each voltage of `images`. The row gains GRAIN_COLUMNS and, for the first
    voltage, LANDING_COLUMNS; `series` holds one row per voltage (LANDING_COLUMNS). The
    chute's and the separator's instances are `instances`' (fmu/reuse.py: a task's, reset
    between its grains), or the grain's own."""
    wall0, cpu0 = time.perf_counter(), time.thread_time()
    chute_spec = RunSpec(chute_params_of(spec.params), spec.t_end, spec.record_interval)
    chute = run_particle(images.chute, chute_spec, instances)
    row = dict(chute.row)  # the chute's outputs at its end
    model = the_charge_model(spec.params, images.models)
    q = float(row[f"charge_to_mass_{model}"])
    exited = bool(row["exited"])
    t_exit = float(row["time_end"])
    inputs = {"u_entry": float(row["u"]), "v_entry": float(row["v"]),
              "charge_to_mass": q} if exited else None
    md = images.separator.model_description()
    chute_s = time.thread_time() - cpu0
    grain = separator_parameters(chute_spec.params, images.settings, 0.0)
    if "x_entry" in spec.params:
        grain["x_entry"] = float(spec.params["x_entry"])
    grain = to_fmu(md, grain)  # once: the voltage alone differs between the flights
    names = list(grain)
    at = names.index("voltage")
    values = list(grain.values())
    released = None if inputs is None else [inputs[name] for name in INPUTS]
    landings = []
    with instance_for(images.separator, "separator", instances) as separator, \
            Flights(images.separator, names, images.horizon, separator) as flights:
        for voltage in images.voltages:
            values[at] = float(voltage)
            flight = flights.fly(values, t_exit, released)
            landings.append({"voltage": float(voltage),
                             **{c: flight[c] for c in LANDING_COLUMNS}})
    first = landings[0]
    row.update(charge_to_mass=q, q_per_m=flight["q_per_m"], mass=flight["mass"],
               equivalent_diameter=flight["equivalent_diameter"])
    row.update({c: first[c] for c in LANDING_COLUMNS})
    row.update(chute_cpu_s=chute_s, cpu_s=time.thread_time() - cpu0,
               wall_s=time.perf_counter() - wall0)
    # the series as columns (batch/sweep.py writes them): a DataFrame made per grain, written
    # and read back by pandas cost more CPU than the grain's flights (docs/line.md, "Benchmark")
    series = {"voltage": np.array([x["voltage"] for x in landings], dtype=np.float64)}
    series.update({c: np.array([x[c] for x in landings],
                               dtype=np.int64 if c in INTEGER_LANDING_COLUMNS else np.float64)
                   for c in LANDING_COLUMNS})
    return RunResult(row, series)


def result_columns(models) -> list[str]:
    """The columns of a grain's results row, for the chute's charge models `models`."""
    return chute_columns(models) + GRAIN_COLUMNS + LANDING_COLUMNS + ["chute_cpu_s"]


def load_images(chute_fmu, separator_fmu, settings: dict, voltages, horizon=SEPARATOR_HORIZON):
    """The FMUs (paths, or 2 / 3 for the build's; default 3) and the line's set-up."""
    return LineImages(FmuImage.load(find_fmu(chute_fmu, "si")),
                      FmuImage.load(find_fmu(separator_fmu, "separator")),
                      dict(settings), tuple(float(v) for v in voltages), float(horizon))

