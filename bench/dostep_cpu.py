"""The CPU of one doStep through the FMUs (docs/work_limit.md): the set-ups that cost the
most per unit of work, each an FMU's defaults with the settings below, in doSteps long
enough for the work limit (its default, 1e6) to end them; the worst CPU of a doStep over up
to eight of them, for FMI 2.0 (which stops at the first Discard) and FMI 3.0.

    .venv/bin/python bench/dostep_cpu.py [build directory, default build] [name filter ...]
"""

import math
import os
import sys
import tempfile
import time

from fmpy import extract

from tribo.fmu import Instance

# The SI set-ups on an unbounded chute: on the default one (0.3 m) the grain leaves within
# the first doStep, long before the limit
ENDLESS = {"chute_length": math.inf}
# (what, FMU, settings, communication step in the FMU's unit of time)
SETUPS = [
    ("SI, epsilon = 1", "tribo_si", {"epsilon": 1.0, **ENDLESS}, 10.0),
    ("SI, epsilon = 1, charging_time = 1e-3", "tribo_si",
     {"epsilon": 1.0, "charging_time": 1e-3, **ENDLESS}, 10.0),
    ("SI, epsilon = 0.001", "tribo_si", {"epsilon": 0.001, **ENDLESS}, 10.0),
    ("SI, gravity = 1e4", "tribo_si", {"gravity": 1e4, **ENDLESS}, 10.0),
    ("SI, gravity = 1e4, 1e5 segments", "tribo_si",
     {"gravity": 1e4, "n_segments": 100000, **ENDLESS}, 10.0),
    ("SI, both Young's moduli 1e3", "tribo_si",
     {"youngs_modulus_particle": 1e3, "youngs_modulus_wall": 1e3, **ENDLESS}, 10.0),
    ("1e5 segments, Sigma_bd = 1e-6", "tribo", {"n_segments": 100000, "Sigma_bd": 1e-6}, 1000.0),
    ("1e5 segments, Sigma_bd = 5e-324", "tribo", {"n_segments": 100000, "Sigma_bd": 5e-324},
     1000.0),
    ("1e5 segments, no limit", "tribo", {"n_segments": 100000}, 1000.0),
    ("1e5 segments, spheroid, Gamma = 10", "tribo",
     {"n_segments": 100000, "grain_geometry": 1, "Gamma": 10.0}, 1000.0),
    ("the same, tau0 = 0", "tribo",
     {"n_segments": 100000, "grain_geometry": 1, "Gamma": 10.0, "tau0": 0.0}, 1000.0),
]
STEPS = 8
DISCARD = 2


def worst_step(fmu_dir, name, settings, h):
    """(CPU of initialization, the worst CPU of a doStep, the statuses)."""
    c0 = time.process_time()
    s = Instance(fmu_dir, name=name)
    s.set_parameters(settings)
    s.init()
    init = time.process_time() - c0
    worst, t, statuses = 0.0, 0.0, []
    for _ in range(STEPS):
        c0 = time.process_time()
        status, reached, early = s.do_step(t, h)
        worst = max(worst, time.process_time() - c0)
        statuses.append(status)
        if status > DISCARD or (status == DISCARD and s.version == 2):
            break  # FMI 2.0: stepFailed until reset
        t = t + h if status == 0 and not early else reached
    s.free()
    return init, worst, statuses


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    only = sys.argv[2:]
    with tempfile.TemporaryDirectory() as unpacked:
        for version in (2, 3):
            for what, fmu, settings, h in SETUPS:
                if only and not any(o in what for o in only):
                    continue
                name = f"{fmu}_fmi{version}"
                fmu_dir = os.path.join(unpacked, name)
                if not os.path.isdir(fmu_dir):
                    extract(os.path.join(build, "fmu", f"{name}.fmu"), fmu_dir)
                init, worst, statuses = worst_step(fmu_dir, fmu, settings, h)
                print(f"FMI {version}.0  {what:34s} doSteps of {h:g}: worst {worst:.3f} s of CPU "
                      f"(initialization {init:.3f} s; statuses {statuses})", flush=True)


if __name__ == "__main__":
    main()
