"""population_profile: where a population's CPU goes in the package (a command, not a test;
docs/populations.md, "Benchmark").

    TRIBO_BUILD_DIR=build .venv/bin/python bench/population_profile.py [N=200]

Runs `tribo population -n N --seed 1 --serial --no-plot` in this process under cProfile,
timed by the process's CPU clock, into a temporary folder, and prints the CPU of each part:
the FMU's calls (the core), the rest of each grain's run, the rows written, the job around
them and the imports. Whichever `tribo` is imported is profiled (PYTHONPATH=<a revision's
python/> for another package on the same FMUs). cProfile's own cost inflates the Python
parts: compare revisions, not these with the core's benchmark.
"""

import contextlib
import cProfile
import io
import pstats
import runpy
import shutil
import sys
import tempfile
import time

PARTS = [  # (what, a test on pstats' (file, line, function) of the calls it sums)
    ("the core: fmi3DoStep", lambda f: f[2] == "_do_step3"),
    ("the core: exitInitializationMode", lambda f: f[2] == "exitInitializationMode"),
    ("the core: instantiate", lambda f: f[2] == "instantiate" and f[0].endswith("instance.py")),
    ("each grain's run (run_particle), the core included", lambda f: f[2] == "run_particle"),
    ("  setting the parameters by name", lambda f: f[2] == "set_parameters"),
    ("the rows written (ResultsFile.append)",
     lambda f: f[2] == "append" and f[0].endswith("results.py")),
    ("the sweep (run_sweep): runs and rows", lambda f: f[2] == "run_sweep"),
    ("the job (batch.job.execute): the sweep, the summary", lambda f: f[2] == "execute"
     and f[0].endswith("job.py")),
]


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    out = tempfile.mkdtemp(prefix="tribo_profile_")
    sys.argv = ["tribo", "population", "-n", str(n), "--seed", "1", "--serial", "--no-plot",
                "--no-progress", "--out", out + "/population"]
    profile = cProfile.Profile(time.process_time)
    profile.enable()
    with contextlib.redirect_stdout(io.StringIO()):  # the command's own lines
        try:
            runpy.run_module("tribo", run_name="__main__")
        except SystemExit:
            pass
    profile.disable()
    shutil.rmtree(out)
    stats = pstats.Stats(profile).stats
    total = max(s[3] for s in stats.values())
    print(f"tribo population -n {n} --seed 1 --serial: {total:.3f} s of CPU under cProfile")
    for what, test in PARTS:
        print(f"  {what}: {sum(s[3] for f, s in stats.items() if test(f)):.3f} s")


if __name__ == "__main__":
    main()
