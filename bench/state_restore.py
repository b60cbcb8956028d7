"""The CPU of the FMU state calls (docs/fmu.md, What a restore costs): for each chute FMU
and integrator, a run of a few communication steps, then the CPU per call of getFMUState, of
setFMUState back into the same instance (what a master that rolls a step back does) and into
a fresh one (which has no model to take the grain's boundary table from), and of serialize +
deserialize, against one doStep of the run's communication step.

    .venv/bin/python bench/state_restore.py [build directory, default build] [calls, default 2000]
"""

import os
import sys
import tempfile
import time

from fmpy import extract

from tribo.fmu import Instance

# (what, FMU, settings, communication step in the FMU's unit of time)
SETUPS = [
    ("fixed step", "tribo", {"integrator": 0, "stick_model": 0}, 0.5),
    ("CVODE Adams", "tribo", {"integrator": 1}, 0.5),
    ("CVODE BDF", "tribo", {"integrator": 2}, 0.5),
    ("SI, defaults", "tribo_si", {}, 1e-3),
]
STEPS = 6
FRESH = 20  # fresh instances, each restored into once


def per_call(function, calls):
    """CPU seconds per call of function() over `calls` calls."""
    started = time.process_time()
    for _ in range(calls):
        function()
    return (time.process_time() - started) / calls


def measure(fmu_dir, name, settings, h, calls):
    s = Instance(fmu_dir, name=name)
    s.set_parameters(settings)
    s.init()
    t = 0.0
    for _ in range(STEPS):
        s.do_step(t, h)
        t += h
    state = s.get_state()
    steps, step = max(calls // 20, 5), 0.0
    for _ in range(steps):  # each from the same point, the restore before it not timed
        s.set_state(state)
        started = time.process_time()
        s.do_step(t, h)
        step += (time.process_time() - started) / steps
    restore = per_call(lambda: s.set_state(state), calls)

    def get():
        s.free_state(s.get_state())

    got = per_call(get, calls)
    data = s.serialize(state)

    def round_trip():
        s.free_state(s.deserialize(s.serialize(state)))

    serialized = per_call(round_trip, calls)
    # a fresh instance has no core: its first restore makes one, the boundary table included
    fresh = [Instance(fmu_dir, name=name) for _ in range(FRESH)]
    started = time.process_time()
    for f in fresh:
        f.set_state(state)
    into_fresh = (time.process_time() - started) / FRESH
    for f in fresh:
        f.free()
    s.free_state(state)
    s.free()
    return {"doStep": step, "getFMUState": got, "setFMUState": restore,
            "setFMUState into a fresh instance": into_fresh,
            "serialize + deserialize": serialized, "bytes": len(data)}


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    calls = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
    with tempfile.TemporaryDirectory() as unpacked:
        for version in (2, 3):
            for what, fmu, settings, h in SETUPS:
                name = f"{fmu}_fmi{version}"
                fmu_dir = os.path.join(unpacked, name)
                if not os.path.isdir(fmu_dir):
                    extract(os.path.join(build, "fmu", f"{name}.fmu"), fmu_dir)
                r = measure(fmu_dir, fmu, settings, h, calls)
                cells = ", ".join(f"{k} {1e6 * v:.0f} µs" for k, v in r.items() if k != "bytes")
                print(f"FMI {version}.0  {what:13s} ({r['bytes']} bytes): {cells}", flush=True)


if __name__ == "__main__":
    main()
