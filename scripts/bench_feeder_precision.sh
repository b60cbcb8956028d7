#!/usr/bin/env bash
# The feeder's accuracy at the default tolerances (docs/feeder.md, "What a feeder costs"): the
# particles `tribo population -n N --seed 1` draws, each dropped onto 0.5 m of the reference
# feeder (50 Hz, 0.5 mm, stroke at 30 degrees, level) and run to the lift-off of its first
# impact (run_end = first_liftoff), at rtol 1e-9 and at rtol 1e-13 (the reference); each
# grain's state, lift-off time and charge set against the reference. With --before REV the
# same for revision REV's core (bench/feeder_state.c compiled against it, as
# scripts/bench_population_core.sh does), against this tree's reference. With MODE = full
# the grains run through the feeder to its end (or 30 s) instead, at the default tolerances
# only, and the run's statistics are printed (a grain's path is chaotic over hundreds of
# impacts: its end is compared as a stream's, not grain by grain).
# Usage: scripts/bench_feeder_precision.sh [--before REV] [N=300] [MODE=first|full]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
n=${1:-300}
mode=${2:-first}
[ -x "$ROOT/build/tribo_feeder_state" ] || "$ROOT/scripts/setup.sh" >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
before_program "$ROOT/bench/feeder_state.c" "$tmp/before"
"$ROOT/.venv/bin/python" "$ROOT/bench/population_feed.py" "$n" 1 > "$tmp/feed.txt"
feeder="chute_length=0.5 tilt=0 vibration_amplitude=5e-4 vibration_frequency=50 vibration_angle=0.5235987755982988"
after="$ROOT/build/tribo_feeder_state"
label=$(tree_label)
runs=("this tree ($label)|$after")
[ -n "$before" ] && runs=("before ($before)|$tmp/before" "${runs[@]}")
if [ "$mode" = full ]; then
  for run in "${runs[@]}"; do
    "${run#*|}" "$tmp/feed.txt" "$feeder" 30 > "$tmp/${run%%|*}.txt"
  done
else
  "$after" "$tmp/feed.txt" "$feeder run_end=1 rtol=1e-13 atol=1e-15" 1 > "$tmp/reference.txt"
  for run in "${runs[@]}"; do
    "${run#*|}" "$tmp/feed.txt" "$feeder run_end=1" 1 > "$tmp/${run%%|*}.txt"
  done
fi
"$ROOT/.venv/bin/python" - "$tmp" "$mode" "${runs[@]%%|*}" <<'PY'
import sys

import numpy as np

folder, mode, names = sys.argv[1], sys.argv[2], sys.argv[3:]
# columns: status, time, X, Y, phi, U, V, Omega, Q_static, Q_sliding, impacts, work_dissipated
if mode == "full":
    for name in names:
        a = np.loadtxt(f"{folder}/{name}.txt", ndmin=2)
        se = lambda v: v.std() / np.sqrt(len(v))
        print(f"{name}: {len(a)} grains, {(a[:, 0] != 8).sum()} not out in 30 s; impacts "
              f"{a[:, 10].mean():.1f} +- {se(a[:, 10]):.1f}; exit time {a[:, 1].mean():.4g} "
              f"+- {se(a[:, 1]):.2g} t*; Q_static {a[:, 8].mean():.5g} +- {se(a[:, 8]):.2g} (mean +- its "
              "standard error)")
    sys.exit()
ref = np.loadtxt(f"{folder}/reference.txt", ndmin=2)
for name in names:
    a = np.loadtxt(f"{folder}/{name}.txt", ndmin=2)
    state = np.max(np.abs(a[:, 2:8] - ref[:, 2:8]), axis=1)
    time = np.abs(a[:, 1] - ref[:, 1])
    charge = np.abs(a[:, 8] - ref[:, 8]) > 1e-12 * np.abs(ref[:, 8])
    print(f"{name}: first impacts of {len(a)} grains against rtol 1e-13: state (X, Y, phi, U, "
          f"V, Omega) median {np.median(state):.2g}, largest {state.max():.2g}; lift-off time "
          f"median {np.median(time):.2g}, largest {time.max():.2g}; charge other than the "
          f"reference's on {charge.sum()} grains")
PY
