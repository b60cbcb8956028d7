"""What a hostile or careless importer passes, for the fuzz suite: values of every kind for
a variable (valid, at and just beyond its bounds, not numbers, denormal, huge, of the C
type's extremes), value references that do not exist, steps and times of every size."""

import math

# C types' extremes by FMI 3.0 function type (FMI 2.0: Integer is an int, Boolean an int)
INT_LIMITS = {"Int8": 8, "Int16": 16, "Int32": 32, "Int64": 64, "Integer": 32, "Boolean": 32}
UINT_LIMITS = {"UInt8": 8, "UInt16": 16, "UInt32": 32, "UInt64": 64}

# valid values that make a run cheap, for the parameters that set its cost; the others take
# any value of their range
CHEAP = {"n_segments": [16, 64, 500, 2000], "dt": [1e-3, 8e-5, 0.1], "work_limit": [1, 50, 1000, 100000, 1000000],
         # mostly no end; else one the drop may reach (or start beyond: refused at initialization)
         "chute_length": [math.inf, math.inf, 1e6, 2.0, 0.05, 5e-324],
         # the separator's: mostly a grain that fits the gap and enters between the plates (else
         # refused at initialization)
         "gap": [0.1, 0.1, 0.02, 10.0, 2e-3], "x_entry": [0.0, 0.0, -0.0, 0.01, -0.03, 0.049],
         # mostly none; else breakdown limits down to far below the saturation, where a model's
         # running sum once rounded at the unheld scale and its own states were refused
         "Sigma_bd": [math.inf, math.inf, math.inf, 1.0, 1e-3, 1e-14, 1e-20, 1e-100, 1e-300],
         "breakdown_density": [2.7e-5, 2.7e-5, 0.0, 1e-3, 1e-12, 1e-20, 1e-100, 1e-300]}
# the expensive ends of those ranges, now and then; and of CVODE's tolerances, where one
# step's charging sweep runs for seconds to minutes past the work limit (the core checks it
# only between steps: its accounting of the work, not the FMU's contract)
COSTLY = {"n_segments": [100000], "dt": [1e-9], "nu": [1e3], "rtol": [1e-14], "atol": [1e-20]}
# the tolerances otherwise, log-uniform short of those ends (their loose ends, rtol to 0.9
# and atol to 1, run at the loosest the event logic takes: docs/model.md §3)
CHEAP_RANGE = {"rtol": (1e-12, 0.9), "atol": (1e-16, 1.0)}

UNKNOWN_VRS = [27, 99, 103, 200, 235, 300, 303, 999, 2**31, 2**32 - 1]


def valid_value(rng, v):
    if v.name in COSTLY and rng.random() < 0.02:
        return rng.choice(COSTLY[v.name])
    if v.name in CHEAP:
        return rng.choice(CHEAP[v.name])
    if v.type == "Boolean":  # (no range: any value; mostly true, which ends runs)
        return rng.choice([0, 1, 1])
    lo, hi = CHEAP_RANGE.get(v.name, (v.min, v.max))
    if v.is_integer:
        return rng.randint(int(lo), int(min(hi, lo + 1000)))
    if lo > 0 and hi / lo > 100:  # log-uniform over a wide positive range
        return math.exp(rng.uniform(math.log(lo), math.log(hi)))
    return rng.uniform(max(lo, -1e3), min(hi, 1e3))


def hostile_value(rng, v, ftype):
    """A value for a variable, for the C type of the function ftype."""
    if ftype in INT_LIMITS or ftype in UINT_LIMITS:
        if ftype in UINT_LIMITS:
            bits = UINT_LIMITS[ftype]
            extremes = [0, 2**bits - 1, 2**(bits - 1)]
        else:
            bits = INT_LIMITS[ftype]
            extremes = [-2**(bits - 1), 2**(bits - 1) - 1, -1, 0]
        candidates = extremes + [1, 2, 3, 4, 16, 100000, 100001]
        if v is not None and v.is_integer:  # bounds and their neighbours (an output has none)
            if math.isfinite(v.min):
                candidates += [int(v.min), int(v.min) - 1]
            if math.isfinite(v.max):
                hi = int(min(v.max, 2**63))
                candidates += [hi, hi + 1]
        return rng.choice(candidates)
    candidates = [math.nan, -math.nan, math.inf, -math.inf, 5e-324, -5e-324, 2.2250738585072014e-308,
                  1e308, -1e308, 1e300, -1e18, 0.0, -0.0, -1.0, 1.0, 0.5]
    if v is not None and math.isfinite(v.min):
        candidates += [v.min, math.nextafter(v.min, -math.inf)]
    if v is not None and math.isfinite(v.max):
        candidates += [v.max, math.nextafter(v.max, math.inf)]
    return rng.choice(candidates)


def step_size(rng, model):
    """A communication step, mostly one an importer would take."""
    sizes = [0.01, 0.1, 0.25, 1.0, 3.0]
    if model.values.get("work_limit", 0) <= 1e6:  # bounded work: long steps end early
        sizes += [40.0, 1e6]
    odd = [0.0, -0.1, math.nan, math.inf, -math.inf, 5e-324, 1e-300, 1e-12, 1e18, 1e300]
    # an importer's steps in the model's units of time (the SI FMU's: t* seconds)
    return rng.choice(odd) if rng.random() < 0.15 else rng.choice(sizes) * model.time_scale()


def communication_point(rng, model):
    """The importer's current time: the FMU's, or the FMU's up to rounding (either side, up
    to nearly all the rounding allowed: at a large time a step may then end before the
    FMU's time), or off it."""
    r = rng.random()
    if r < 0.85:
        return model.time
    if r < 0.92:
        allowance = 0.9 * model.rounding_tolerance()
        return rng.choice([model.time * (1 + 1e-12) + 1e-12, model.time - allowance,
                           model.time + allowance])
    return rng.choice([model.time + 1.0, model.time - 0.5, math.nan, math.inf, -1e300])


def experiment(rng):
    """A start time, a stop time and a tolerance (None: undefined). Large start times are
    those where the FMU's time is coarse: at 1e9 it may be off by 1 (rounding), from 1e15 it
    moves by 0.125."""
    start = rng.choice([0.0, 0.0, 0.0, 1.5, -3.0, 1e6, 1e9, 1e12, 1e15, 1e300, math.nan, math.inf])
    stop = rng.choice([None, None, None, start + 5.0, start + 1e6, start - 1.0, math.nan])
    # valid tolerances, and ones out of rtol's range [1e-14, 1). Not its tight end: at rtol =
    # 1e-14 one CVODE step's charging sweep can run for minutes (1e-12: seconds), the work
    # limit being checked only between steps (the core's accounting of the work, not the
    # FMU's contract, which these tolerances test)
    # (from 0.05 on, loose ones once ended in an event cascade, or crept by 1e-6 per doStep)
    tolerance = rng.choice([None, None, None, 1e-4, 1e-6, 1e-9, 0.05, 0.1, 0.5, 0.99, 2.0, 0.0,
                            -1e-6, math.nan])
    return start, stop, tolerance
