#!/usr/bin/env bash
# A package command's runs against the core alone, the same runs, in one run (docs/line.md,
# docs/populations.md "Charge-per-impact maps", docs/calibration.md: "Benchmark"): the core's
# CPU (bench/runs_core.c: the runs the command makes, written by bench/runs_feed.py, through
# the C API one after another) and the CPU of the whole command (every process it starts, its
# Dask workers included: its and its children's user and system time, the system's apart),
# serially, on the local cluster's 2 threads and on 2 worker processes, and the ratio of each
# to the core's. KIND:
#   impact-map  tribo impact-map over a grid of 10 speeds x 6 angles x 6 orientations x 6
#               roundnesses (2160 episodes)
#   line        tribo line sweep -n 1000 --seed 1 at 4 voltages (1000 chute runs, 4000 flights)
#   calibrate   tribo calibrate against bench/calibration_data.py's 20 impacts and 3 chute
#               runs of 50 grains (every run its fit asks for: runs_feed.py runs it once, serially,
#               to record them)
#   all         the three above, one after the other, each with its table
# With --before REV the package of revision REV (its python/tribo, on this build's FMUs) runs
# each command first, so that one run gives the before and the after under the same load.
# ROUNDS > 1 repeats it all and gives each number's median. The core also runs split in two
# halves on 2 processes at once: the parallel modes' CPU against it too (bench_modes.sh).
# Usage: [TRIBO_PYTHON=...] scripts/bench_runs_package.sh [--before REV] KIND [ROUNDS=1]
#   e.g. scripts/bench_runs_package.sh all 3: every mode's ratio for the three commands
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
kind=${1:?"usage: $0 [--before REV] impact-map|line|calibrate|all [ROUNDS]"}
rounds=${2:-1}
if [ "$kind" = all ]; then
  for kind in impact-map line calibrate; do
    "$ROOT/scripts/bench_runs_package.sh" ${before:+--before "$before"} "$kind" "$rounds"
    echo
  done
  exit 0
fi
# TRIBO_PYTHON: another interpreter with the package's requirements (a git worktree's without
# a venv of its own); the set-up (scripts/setup.sh) is then the caller's
if [ -z "${TRIBO_PYTHON:-}" ]; then
  "$ROOT/scripts/setup.sh" >/dev/null
fi
PYTHON=${TRIBO_PYTHON:-$ROOT/.venv/bin/python}
export TRIBO_BUILD_DIR="$ROOT/build"
# under the checkout's out/, where the commands write by default: a new file costs this
# machine's /tmp ten times the CPU it costs here, and a line writes a file per grain
mkdir -p "$ROOT/out"
tmp=$(mktemp -d "$ROOT/out/bench_runs_package.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
before_package "$tmp"
case "$kind" in
  impact-map) args=(impact-map --speed 0.25:8:10 --angle-deg 15:90:6 --phi0-deg 0:150:6
                    --epsilon 0.4:1:6) ;;
  line) args=(line sweep -n 1000 --seed 1 --voltages 5e3:40e3:4) ;;
  calibrate)
    PYTHONPATH="$ROOT/python" "$PYTHON" "$ROOT/bench/calibration_data.py" "$tmp" >/dev/null
    args=(calibrate --impacts "$tmp/impacts.csv" --chutes "$tmp/chutes.csv") ;;
  *) echo "KIND $kind: impact-map, line, calibrate or all" >&2; exit 2 ;;
esac
PYTHONPATH="$ROOT/python" "$PYTHON" "$ROOT/bench/runs_feed.py" "${args[@]}" --no-plot \
  > "$tmp/feed.txt" 2> "$tmp/feed.log" || { cat "$tmp/feed.log"; exit 1; }
voltages=$(sed -n 's/^voltages //p' "$tmp/feed.log")
# shellcheck source=bench_modes.sh
. "$ROOT/scripts/bench_modes.sh"
# the same runs split in two (every other one), for the core on 2 processes at once: two busy
# processes on this machine's 2 cores each take more CPU for the same work than one alone,
# which the package's 2 threads or 2 worker processes pay too
awk 'NR % 2 == 1' "$tmp/feed.txt" > "$tmp/feed_1.txt"
awk 'NR % 2 == 0' "$tmp/feed.txt" > "$tmp/feed_2.txt"
cpu_in() { sed -E 's/.*CPU ([0-9.]+) s.*/\1/' "$1"; }
for ((r = 1; r <= rounds; r++)); do
  core=$("$ROOT/build/tribo_runs_core" "$tmp/feed.txt" $voltages)
  echo "core $(echo "$core" | sed -E 's/.*CPU ([0-9.]+) s.*/\1/')" >> "$tmp/results.txt"
  echo "$core" > "$tmp/core.txt"
  "$ROOT/build/tribo_runs_core" "$tmp/feed_1.txt" $voltages > "$tmp/core_1.txt" &
  "$ROOT/build/tribo_runs_core" "$tmp/feed_2.txt" $voltages > "$tmp/core_2.txt"
  wait
  echo "core-2 $(awk -v a="$(cpu_in "$tmp/core_1.txt")" -v b="$(cpu_in "$tmp/core_2.txt")" \
    'BEGIN { print a + b }')" >> "$tmp/results.txt"
  modes_run "$tmp/results.txt" "${args[@]}"
done
modes_report "$tmp/results.txt" "tribo $kind (the core: $(cat "$tmp/core.txt"))" "$rounds"
