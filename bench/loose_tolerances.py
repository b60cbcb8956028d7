"""Which tolerances the event logic takes (docs/model.md §3, "the loosest tolerances"): the
core (build/fmu/tribo_reference_run) from the drop to tau = 100 in seven set-ups on a grid
of rtol and atol, each run reported as reaching the end or not and why. CVODE works to at
most rtol 1e-3 and atol 1e-5 (src/chute/model.h): on a build with those limits every run
reaches the end; the grid's failures, without them, say where the limits must lie.

    .venv/bin/python bench/loose_tolerances.py [build directory, default build]
"""

import json
import os
import subprocess
import sys

SETUPS = [{}, {"mu": 1.0, "nu": 1.0}, {"epsilon": 0.3}, {"mu": 0.5, "nu": 0.1, "epsilon": 0.8},
          {"integrator": 2}, {"Omega0": 50}, {"mu": 1, "nu": 0.1, "Gamma": 1e-5}]
RTOLS = [1e-6, 1e-4, 1e-3, 1e-2, 0.1, 0.5]
ATOLS = [1e-8, 1e-6, 1e-5, 1e-4, 1e-3]
T_END = 100.0


def run(exe, params):
    """(whether the run reached T_END, the core's error or X there)."""
    lines = [f"set {k} {float(v)!r}" for k, v in params.items()] + \
        ["create", f"advance {T_END!r}", "print"]
    out = subprocess.run([exe], input="\n".join(lines) + "\n", capture_output=True, text=True,
                         timeout=600)
    record = json.loads(out.stdout.splitlines()[-1])
    return ("error" not in record, record.get("error", record.get("X")))


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else "build"
    exe = os.path.join(build, "fmu", "tribo_reference_run")
    failed = 0
    for setup in SETUPS:
        for rtol in RTOLS:
            for atol in ATOLS:
                ok, what = run(exe, dict(setup, rtol=rtol, atol=atol))
                failed += not ok
                print(f"{json.dumps(setup)} rtol {rtol:g} atol {atol:g}: "
                      f"{'end, X = ' if ok else 'FAILED: '}{what}")
    print(f"{failed} of {len(SETUPS) * len(RTOLS) * len(ATOLS)} runs did not reach tau = {T_END:g}")


if __name__ == "__main__":
    main()
