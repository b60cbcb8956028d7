#!/usr/bin/env bash
# A population through the package against the core alone, the same grains, in one run
# (docs/populations.md, "Benchmark"): the core's CPU (bench/population_core.c: the grains
# `tribo population -n N --seed 1` draws, through the SI C API one by one) and the CPU of the
# whole command `tribo population -n N --seed 1` (every process it starts, its Dask workers
# included: the command's and its children's user and system time), serially, on the local
# cluster's 2 threads and on 2 worker processes, and the ratio of each to the core's. With
# --before REV the package of revision REV (its python/tribo, on this build's FMUs) runs each
# command first, so that one run gives the before and the after under the same load.
# ROUNDS > 1 repeats it all and gives each number's median.
# Usage: scripts/bench_population_package.sh [--before REV] [N=1000] [ROUNDS=1]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
n=${1:-1000}
rounds=${2:-1}
"$ROOT/scripts/setup.sh" >/dev/null
PYTHON="$ROOT/.venv/bin/python"
export TRIBO_BUILD_DIR="$ROOT/build"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
before_package "$tmp"
"$PYTHON" "$ROOT/bench/population_feed.py" "$n" 1 > "$tmp/feed.txt"
# the CPU of a command and of every process it waited for, in seconds
cpu_of() {
  "$PYTHON" - "$@" <<'PY'
import resource
import subprocess
import sys

subprocess.run(sys.argv[1:], check=True, stdout=subprocess.DEVNULL)
used = resource.getrusage(resource.RUSAGE_CHILDREN)
print(f"{used.ru_utime + used.ru_stime:.3f}")
PY
}
modes=(serial threads processes)
declare -A options=([serial]="--serial" [threads]="--workers 2" [processes]="--workers 2 --processes")
for ((r = 1; r <= rounds; r++)); do
  core=$("$ROOT/build/tribo_population_core" "$tmp/feed.txt")
  echo "core $(echo "$core" | sed -E 's/.*CPU ([0-9.]+) s.*/\1/')" >> "$tmp/results.txt"
  for mode in "${modes[@]}"; do
    for label in ${before:+before} after; do
      rm -rf "$tmp/out"
      if [ "$label" = before ]; then
        command=(env PYTHONPATH="$tmp/before/python" "$PYTHON" -m tribo)
      else
        command=(env PYTHONPATH="$ROOT/python" "$PYTHON" -m tribo)
      fi
      # shellcheck disable=SC2086
      echo "$mode-$label $(cpu_of "${command[@]}" population -n "$n" --seed 1 ${options[$mode]} \
        --out "$tmp/out" --no-progress --no-plot)" >> "$tmp/results.txt"
    done
  done
done
"$PYTHON" - "$tmp/results.txt" "$n" "$rounds" "${before:+$(git -C "$ROOT" rev-parse --short "$before")}" \
  "$(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- python src || echo ', modified')" <<'PY'
import statistics
import sys

path, n, rounds, before, after = sys.argv[1:]
got = {}
for line in open(path):
    name, value = line.split()
    got.setdefault(name, []).append(float(value))
median = {name: statistics.median(values) for name, values in got.items()}
core = median["core"]
print(f"{n} grains of the reference feed (seed 1), the median of {rounds} round(s); the core "
      f"alone: {core:.2f} s of CPU")
print()
labels = (["before"] if before else []) + ["after"]
names = {"before": f"before ({before})", "after": f"this tree ({after})"}
print("| executor | " + " | ".join(f"{names[l]}: CPU [s], / core" for l in labels) + " |")
print("|---|" + "---|" * len(labels))
for mode, text in (("serial", "in this process (--serial)"), ("threads", "2 threads (--workers 2)"),
                   ("processes", "2 worker processes (--workers 2 --processes)")):
    cells = [f"{median[f'{mode}-{l}']:.2f}, {median[f'{mode}-{l}'] / core:.2f}x" for l in labels]
    print(f"| {text} | " + " | ".join(cells) + " |")
PY
