#!/usr/bin/env bash
# The dimensionless rigid disc rolling 2e5 tau (bench/rigid_disc.c; docs/reference_case.md,
# "The rolling disc's charging"): its CPU and what it gives. With --before REV the same
# benchmark is also compiled against revision REV's core (built in a temporary folder) and
# run first, so that one run of this command gives the before and the after on the same
# machine. Usage: scripts/bench_rigid_disc.sh [--before REV] [rounds=5]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
"$ROOT/scripts/setup.sh" >/dev/null
if [ -n "$before" ]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  before_program "$ROOT/bench/rigid_disc.c" "$tmp/before"
  echo "before ($(git -C "$ROOT" rev-parse --short "$before")): $("$tmp/before" "$@")"
fi
echo "this tree ($(tree_label)): $("$ROOT/build/tribo_bench_rigid_disc" "$@")"
