#!/usr/bin/env bash
# The core's cost of a population (bench/population_core.c; docs/populations.md, "The core's
# cost"): the particles `tribo population -n N --seed 1` draws, run through the SI C API one
# by one, each grain's CPU measured alone: the reference feed, the same at mu = 0.5, and
# discs (epsilon = 1) at mu = 0.5. With --before REV the benchmark is also compiled against
# revision REV's core (built in a temporary folder), at that revision's defaults, and the two
# run in turn, ROUNDS times, so that one run of this command gives the before and the after
# under the same load. Usage: scripts/bench_population_core.sh [--before REV] [N=1000] [ROUNDS=1]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
n=${1:-1000}
rounds=${2:-1}
"$ROOT/scripts/setup.sh" >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
before_program "$ROOT/bench/population_core.c" "$tmp/before"
declare -A feeds=([reference]="" [mu0.5]="mu=0.5" [discs-mu0.5]="epsilon=1 mu=0.5")
for name in reference mu0.5 discs-mu0.5; do
  # shellcheck disable=SC2086
  "$ROOT/.venv/bin/python" "$ROOT/bench/population_feed.py" "$n" 1 ${feeds[$name]} > "$tmp/$name.txt"
done
after="$ROOT/build/tribo_population_core"
label=$(tree_label)
for ((r = 1; r <= rounds; r++)); do
  for name in reference mu0.5 discs-mu0.5; do
    if [ -n "$before" ]; then
      echo "$name, before ($before): $("$tmp/before" "$tmp/$name.txt")"
    fi
    echo "$name, this tree ($label): $("$after" "$tmp/$name.txt")"
  done
done
