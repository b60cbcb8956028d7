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
# Usage: [TRIBO_PYTHON=...] scripts/bench_population_package.sh [--before REV] [N=1000] [ROUNDS=1]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
n=${1:-1000}
rounds=${2:-1}
# TRIBO_PYTHON: another interpreter with the package's requirements (a git worktree's without
# a venv of its own); the set-up (scripts/setup.sh) is then the caller's
if [ -z "${TRIBO_PYTHON:-}" ]; then
  "$ROOT/scripts/setup.sh" >/dev/null
fi
PYTHON=${TRIBO_PYTHON:-$ROOT/.venv/bin/python}
export TRIBO_BUILD_DIR="$ROOT/build"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
before_package "$tmp"
"$PYTHON" "$ROOT/bench/population_feed.py" "$n" 1 > "$tmp/feed.txt"
# shellcheck source=bench_modes.sh
. "$ROOT/scripts/bench_modes.sh"
for ((r = 1; r <= rounds; r++)); do
  core=$("$ROOT/build/tribo_population_core" "$tmp/feed.txt")
  echo "core $(echo "$core" | sed -E 's/.*CPU ([0-9.]+) s.*/\1/')" >> "$tmp/results.txt"
  modes_run "$tmp/results.txt" population -n "$n" --seed 1
done
modes_report "$tmp/results.txt" "$n grains of the reference feed (seed 1)" "$rounds"
