"""LIGGGHTS as a separate process: `liggghts -in in.liggghts` in the run's folder, or
`mpirun -np N liggghts ...` for N ranks; its progress read from its thermo lines (step,
grains in the box), its failure said in one line (LIGGGHTS' own ERROR line), its CPU time
measured (the child's user + system time, all ranks).

LIGGGHTS stops a run it is signalled to stop (Ctrl-C: SIGINT) at the step it is at and
writes a restart file (restart_forced_liggghts_<step>.data): `on_stop(cpu)` is then told
the CPU spent, and the runner resumes from that file (script.py's restart input). A run
that fails otherwise starts over. A run that finished is kept (`DONE` in its folder): the
charging, which reads its outputs, is what runs again.
"""

import os
import re
import shutil
import subprocess
import time

from tqdm.auto import tqdm

DONE = "done.json"
STOP_WAIT = 120  # s: what LIGGGHTS is given to write its restart file once signalled
THERMO = re.compile(r"^\s*(\d+)\s+(\d+)\s*$")


class EngineError(RuntimeError):
    """LIGGGHTS missing or failed (the message, one line, says which and why)."""


def command(ranks: int) -> list[str]:
    """The command line of a LIGGGHTS run on `ranks` MPI ranks (EngineError where LIGGGHTS
    or mpirun is missing)."""
    if shutil.which("liggghts") is None:
        raise EngineError("liggghts: not found (Debian 12: apt-get install liggghts; "
                          "scripts/setup.sh installs it)")
    if ranks == 1:
        # its screen is a pipe here, which the C library fills in blocks: line-buffered, the
        # progress comes as it runs (Open MPI forwards a rank's lines as they come)
        return (["stdbuf", "-oL"] if shutil.which("stdbuf") else []) + ["liggghts"]
    if shutil.which("mpirun") is None:
        raise EngineError(f"ranks = {ranks}: mpirun not found (it comes with liggghts' "
                          f"Open MPI)")
    # as root (a container) Open MPI refuses to start without being told
    extra = ["--allow-run-as-root"] if os.geteuid() == 0 else []
    return ["mpirun", *extra, "--oversubscribe", "-np", str(ranks), "liggghts"]


def run(folder: str, input_name: str, log_name: str, steps: int, ranks: int = 1, *,
        progress: bool = True, first_step: int = 0, on_stop=None) -> float:
    """Run the input in `folder`; returns LIGGGHTS' CPU time (s). EngineError, one line,
    where it fails: its ERROR line, or its exit status; where it was stopped by a signal,
    on_stop(cpu) first (the module's text)."""
    on_stop = on_stop or (lambda cpu: None)
    argv = command(ranks) + ["-in", input_name, "-log", log_name, "-echo", "none"]
    before = os.times()
    bar = tqdm(total=steps, initial=first_step, desc="DEM steps", unit="step",
               disable=not progress, unit_scale=True)
    started = time.perf_counter()
    try:
        proc = subprocess.Popen(argv, cwd=folder, stdout=subprocess.PIPE,
                                stderr=subprocess.STDOUT, text=True, errors="replace", bufsize=1)
        try:
            for line in proc.stdout:
                m = THERMO.match(line)
                if m:
                    step = int(m.group(1))
                    bar.update(max(0, min(step, steps) - bar.n))
        except KeyboardInterrupt:
            # LIGGGHTS, in the same process group, has the signal too: it writes its restart
            # file and stops; it is ended only where it does not
            try:
                proc.wait(timeout=STOP_WAIT)
            except subprocess.TimeoutExpired:
                proc.terminate()
                proc.wait()
            on_stop(_cpu(before))
            raise
        code = proc.wait()
        if code == 0:  # the run ends once every grain has left: its steps are all it took
            bar.total = bar.n
            bar.refresh()
    finally:
        bar.close()
    cpu = _cpu(before)
    log = os.path.join(folder, log_name)
    if code != 0 or _error(log) or _forced(log):
        # LIGGGHTS stops a run it is signalled to stop (SIGINT, SIGTERM) itself, writing a
        # restart file, and exits 0: the outputs then end early
        if _forced(log) and not _error(log):
            on_stop(cpu)
            raise EngineError("LIGGGHTS was stopped by a signal and wrote a restart file: "
                              "the same command resumes from it")
        reason = _error(log) or f"exit status {code}"
        raise EngineError(f"LIGGGHTS failed after {time.perf_counter() - started:.1f} s: "
                          f"{reason} (log: {os.path.join(folder, log_name)})")
    return cpu


def _cpu(before) -> float:
    after = os.times()
    return (after.children_user - before.children_user) + (after.children_system
                                                           - before.children_system)


def _forced(log: str) -> bool:
    """Whether LIGGGHTS stopped early on a signal (its log says it wrote a forced restart)."""
    if not os.path.exists(log):
        return False
    with open(log, errors="replace") as f:
        return any("Forced restart" in line for line in f)


def _error(log: str) -> str | None:
    """LIGGGHTS' first ERROR line in its log, or None."""
    if not os.path.exists(log):
        return None
    with open(log, errors="replace") as f:
        for line in f:
            if line.startswith("ERROR"):
                return line.strip()
    return None
