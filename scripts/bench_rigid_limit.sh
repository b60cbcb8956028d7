#!/usr/bin/env bash
# The rigid stick against the compliant one as Gamma falls (bench/rigid_limit.c;
# docs/reference_case.md, "Rigid and compliant stick"): grains placed on a chute, both stick
# models to the exit at Gamma = 1e-3 ... 1e-6, a markdown table.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh" >/dev/null
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
echo "== $(tree_label), $(nproc) cores"
"$ROOT/build/tribo_bench_rigid_limit"
