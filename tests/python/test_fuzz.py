"""The fuzz suite (tests/fuzz/fuzz_fmu.py) over the FMUs (the dimensionless pair, and fewer
sequences on the SI pair and the separator's, whose runs are cheap): random call sequences checked
against a model of the expected statuses, and mutated FMU states, with fixed seeds and a
timeout per call (a hang guard); on the Release build also the work limit's bound, one
doStep of each of the costliest set-ups at the declared extremes (front_ends.py). Once on
the Release build and once on the sanitizer build (build-sanitize:
AddressSanitizer and UndefinedBehaviorSanitizer with float-cast-overflow; the FMU's library
is loaded with the sanitizer runtime preloaded). One test per FMU and build, so that
pytest's workers (pytest-xdist, scripts/test.sh) share them out (a longer campaign with other
seeds: scripts/fuzz.sh); each run's counts are written to <build>/fuzz/*.json and printed."""

import json
import os
import subprocess
import sys

import pytest

from tribo_fmu import BUILD_DIR, ROOT

SANITIZE_DIR = os.path.abspath(os.environ.get("TRIBO_SANITIZE_BUILD_DIR",
                                              os.path.join(ROOT, "build-sanitize")))
FUZZ = os.path.join(ROOT, "tests", "fuzz", "fuzz_fmu.py")

# Each FMU's pair of FMI versions with the same budgets: (build, FMU, the FMI 2.0 run's seed
# (the 3.0 run's is the next), sequences, states mutated, values per field, seconds per call).
# Fixed seeds, so that the suite repeats the same sequences as a regression check; a campaign
# with new seeds and larger budgets is scripts/fuzz.sh (TRIBO_FUZZ_SCALE, TRIBO_FUZZ_SEED)
PAIRS = [
    (BUILD_DIR, "tribo", 11, 125, 4, 4, 20),
    (SANITIZE_DIR, "tribo", 13, 30, 2, 2, 120),
    (BUILD_DIR, "tribo_si", 15, 30, 2, 2, 20),
    (SANITIZE_DIR, "tribo_si", 17, 8, 1, 1, 120),
    (BUILD_DIR, "tribo_separator", 19, 150, 8, 3, 20),
    (SANITIZE_DIR, "tribo_separator", 21, 40, 4, 2, 120),
]
RUNS = [(build, f"{fmu}_fmi{version}", seed + version - 2, *budgets)
        for build, fmu, seed, *budgets in PAIRS for version in (2, 3)]
# scripts/fuzz.sh: every budget times SCALE, every seed plus SEED
SCALE = int(os.environ.get("TRIBO_FUZZ_SCALE", "1"))
SEED = int(os.environ.get("TRIBO_FUZZ_SEED", "0"))


def sanitizer_runtime():
    """The sanitizer libraries of the compiler the build used, to preload into Python."""
    libraries = []
    for name in ("libasan.so", "libubsan.so"):
        path = subprocess.run(["cc", f"-print-file-name={name}"], capture_output=True,
                              text=True).stdout.strip()
        if not os.path.isabs(path):
            pytest.fail(f"the compiler does not know where {name} is")
        libraries.append(path)
    return " ".join(libraries)


def fuzz(run):
    build, name, seed, sequences, bases, per_field, timeout = run
    seed, sequences, bases = seed + SEED, sequences * SCALE, bases * SCALE
    fmu = os.path.join(build, "fmu", f"{name}.fmu")
    summary = os.path.join(build, "fuzz", f"{name}_seed{seed}.json")
    os.makedirs(os.path.dirname(summary), exist_ok=True)
    if os.path.exists(summary):
        os.remove(summary)
    env = dict(os.environ)
    if build == SANITIZE_DIR:
        # a report ends the process with its own exit status (Python leaks by design)
        env.update(LD_PRELOAD=sanitizer_runtime(), ASAN_OPTIONS="detect_leaks=0:exitcode=86",
                   UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=87")
    command = [sys.executable, FUZZ, fmu, "--seed", str(seed), "--sequences", str(sequences),
               "--mutation-bases", str(bases), "--values-per-field", str(per_field),
               "--timeout", str(timeout), "--json", summary]
    if build != SANITIZE_DIR:
        # the work limit's bound at the declared extremes, 1e5 segments with the breakdown
        # limit among them (in an optimised build: the bound is about CPU time there)
        command.append("--work-bound")
    done = subprocess.run(command, env=env, capture_output=True, text=True)
    return run, summary, done


def run_id(run):
    return f"{os.path.basename(run[0])}-{run[1]}"


@pytest.mark.parametrize("run", RUNS, ids=run_id)
def test_the_fuzz_suite_finds_nothing_wrong(run):
    build, name, *_ = run
    if not os.path.exists(os.path.join(build, "fmu", f"{name}.fmu")):
        pytest.fail(f"{build}/fmu/{name}.fmu is missing: build it "
                    f"(scripts/test.sh builds build-sanitize with the FMUs)")
    run, summary, done = fuzz(run)
    what = f"{os.path.basename(run[0])} {run[1]} (seed {run[2] + SEED})"
    # a crash, a sanitizer report or a timeout ends the process otherwise than by 0 / 1
    assert done.returncode in (0, 1) and os.path.exists(summary), \
        f"{what}: exit {done.returncode}\n{done.stderr[-4000:]}"
    with open(summary) as f:
        counts = json.load(f)
    print(f"{what}: {counts['sequences']} sequences, {counts['calls']} calls, "
          f"{counts['mutated_states']} mutated states, {counts['seconds']} s "
          f"(slowest call {counts['slowest_call_seconds']} s, "
          f"{len(counts['core_failures'])} failures of the core reported, "
          f"{counts['exits']} exits from the chute; {counts['refusals_unchanged']} refused "
          f"calls changed nothing, {counts['own_states_restored']} own states restored, "
          f"{len(counts['own_states_refused_past_a_tiny_chute'])} own states refused past "
          f"a chute of at most 1e-250; the costliest set-ups at the default work limit: "
          f"{len(counts['work_bound_steps'])} doSteps, the slowest "
          f"{max([w['cpu_seconds'] for w in counts['work_bound_steps']], default=0)} s of CPU)")
    assert not counts["findings"], f"{what}: " + json.dumps(counts["findings"][:3], indent=1)
