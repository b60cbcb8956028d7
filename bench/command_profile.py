"""command_profile: where a package command's CPU goes (a command, not a test; docs/line.md,
docs/populations.md and docs/calibration.md, "Benchmark").

    TRIBO_BUILD_DIR=build .venv/bin/python bench/command_profile.py COMMAND [ARGS...]

e.g. `bench/command_profile.py line sweep -n 200 --seed 1 --voltages 5e3:40e3:4` or
`bench/command_profile.py population -n 200 --seed 1`. Runs
`tribo COMMAND ARGS --serial --no-plot --no-progress` in this process under cProfile, timed by
the process's CPU clock, into a temporary folder, and prints the CPU of each part the command
has: the FMU's calls (the core), each run's function, the files written and read, the job
around them, and what is left (the imports, the command). Whichever `tribo` is imported is
profiled (PYTHONPATH=<a revision's python/> for another package on the same FMUs). cProfile's
own cost inflates the Python parts: compare revisions, not these with the core's benchmark.
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

PARTS = [  # (what, the (file's end, function) whose cumulative CPU it is)
    ("the core: fmi3DoStep", ("instance.py", "_do_step3")),
    ("the core: exitInitializationMode", ("fmi3.py", "exitInitializationMode")),
    ("the core: instantiate", ("instance.py", "instantiate")),
    ("the FMU's instances made (Instance)", ("instance.py", "__init__")),
    ("  and freed", ("instance.py", "free")),
    ("parameters set by name (Instance.set_parameters)", ("instance.py", "set_parameters")),
    ("  every value set (Instance.set)", ("instance.py", "set")),
    ("each grain's run down the chute (run_particle), the core included",
     ("particle.py", "run_particle")),
    ("a line's grain (run_line_grain): its chute and flights, the core included",
     ("grain.py", "run_line_grain")),
    ("  its flights (Flights.fly)", ("grain.py", "fly")),
    ("an impact episode (run_episode), the core included", ("episode.py", "run_episode")),
    ("a calibration's batch of runs (run_runs), the core included", ("observables.py", "run_runs")),
    ("the rows written (ResultsFile.append)", ("results.py", "append")),
    ("the series written (write_series)", ("sweep.py", "write_series")),
    ("the landings collected (collect_landings)", ("mixture.py", "collect_landings")),
    ("the sweep (run_sweep): runs and rows", ("sweep.py", "run_sweep")),
    ("the calibration's fit (fit_pair)", ("fit.py", "fit_pair")),
    ("the job (batch.job.execute): runs, rows, what is made of them", ("job.py", "execute")),
]


def main():
    out = tempfile.mkdtemp(prefix="tribo_profile_")
    command = sys.argv[1:]
    sys.argv = ["tribo", *command, "--serial", "--no-plot", "--no-progress", "--out",
                out + "/out"]
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
    print(f"tribo {' '.join(command)} --serial: {total:.3f} s of CPU under cProfile")
    job = 0.0
    for what, (file, function) in PARTS:
        spent = sum(s[3] for f, s in stats.items() if f[0].endswith(file) and f[2] == function)
        if function == "execute":
            job = spent
        if spent:
            print(f"  {what}: {spent:.3f} s")
    print(f"  the rest: the imports, the command: {total - job:.3f} s")


if __name__ == "__main__":
    main()
