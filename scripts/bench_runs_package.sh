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
# With --before REV the package of revision REV (its python/tribo, on this build's FMUs) runs
# each command first, so that one run gives the before and the after under the same load.
# ROUNDS > 1 repeats it all and gives each number's median.
# Usage: [TRIBO_PYTHON=...] scripts/bench_runs_package.sh [--before REV] KIND [ROUNDS=1]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
kind=${1:?"usage: $0 [--before REV] impact-map|line|calibrate [ROUNDS]"}
rounds=${2:-1}
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
  *) echo "KIND $kind: impact-map, line or calibrate" >&2; exit 2 ;;
esac
PYTHONPATH="$ROOT/python" "$PYTHON" "$ROOT/bench/runs_feed.py" "${args[@]}" --no-plot \
  > "$tmp/feed.txt" 2> "$tmp/feed.log" || { cat "$tmp/feed.log"; exit 1; }
voltages=$(sed -n 's/^voltages //p' "$tmp/feed.log")
# the CPU of a command and of every process it waited for, and the system's part of it, in
# seconds (a file made costs system time: a line makes one per grain)
cpu_of() {
  "$PYTHON" - "$@" <<'PY'
import resource
import subprocess
import sys

subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL)
used = resource.getrusage(resource.RUSAGE_CHILDREN)
print(f"{used.ru_utime + used.ru_stime:.3f} {used.ru_stime:.3f}")
PY
}
modes=(serial threads processes)
declare -A options=([serial]="--serial" [threads]="--workers 2" [processes]="--workers 2 --processes")
for ((r = 1; r <= rounds; r++)); do
  core=$("$ROOT/build/tribo_runs_core" "$tmp/feed.txt" $voltages)
  echo "core $(echo "$core" | sed -E 's/.*CPU ([0-9.]+) s.*/\1/') 0" >> "$tmp/results.txt"
  for mode in "${modes[@]}"; do
    for label in ${before:+before} after; do
      rm -rf "$tmp/out"
      if [ "$label" = before ]; then
        command=(env PYTHONPATH="$tmp/before/python" "$PYTHON" -m tribo)
      else
        command=(env PYTHONPATH="$ROOT/python" "$PYTHON" -m tribo)
      fi
      # shellcheck disable=SC2086
      echo "$mode-$label $(cpu_of "${command[@]}" "${args[@]}" ${options[$mode]} \
        --out "$tmp/out" --no-progress --no-plot)" >> "$tmp/results.txt"
    done
  done
done
"$PYTHON" - "$tmp/results.txt" "$kind" "$core" "$rounds" \
  "${before:+$(git -C "$ROOT" rev-parse --short "$before")}" \
  "$(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- python src || echo ', modified')" <<'PY'
import statistics
import sys

path, kind, core_line, rounds, before, after = sys.argv[1:]
got, system = {}, {}
for line in open(path):
    name, value, sys_part = line.split()
    got.setdefault(name, []).append(float(value))
    system.setdefault(name, []).append(float(sys_part))
median = {name: statistics.median(values) for name, values in got.items()}
median_system = {name: statistics.median(values) for name, values in system.items()}
core = median["core"]
print(f"tribo {kind}, the median of {rounds} round(s); the core alone ({core_line.strip()}): "
      f"{core:.2f} s of CPU")
print()
labels = (["before"] if before else []) + ["after"]
names = {"before": f"before ({before})", "after": f"this tree ({after})"}
print("| executor | " + " | ".join(f"{names[l]}: CPU [s] (the system's), / core" for l in labels)
      + " |")
print("|---|" + "---|" * len(labels))
for mode, text in (("serial", "in this process (--serial)"), ("threads", "2 threads (--workers 2)"),
                   ("processes", "2 worker processes (--workers 2 --processes)")):
    cells = [f"{median[f'{mode}-{l}']:.2f} ({median_system[f'{mode}-{l}']:.2f}), "
             f"{median[f'{mode}-{l}'] / core:.2f}x" for l in labels]
    print(f"| {text} | " + " | ".join(cells) + " |")
PY
