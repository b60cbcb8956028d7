#!/usr/bin/env bash
# The work limit measured (bench/work_limit.c; docs/fmu.md, "The work limit"): the CPU of a
# unit of work per kind, ordinary use within the default, and the slowest advance over
# random scenes at the ends of the parameters' ranges.
# Usage: scripts/bench_work_limit.sh [scenes=300] [seed=1]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh" >/dev/null
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
echo "== $(tree_label), $(nproc) cores"
"$ROOT/build/tribo_bench_work_limit" "$@"
