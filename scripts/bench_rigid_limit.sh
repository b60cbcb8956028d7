#!/usr/bin/env bash
# The rigid stick against the compliant one as Gamma falls (bench/rigid_limit.c;
# docs/reference_case.md, "Rigid and compliant stick"): grains placed on a chute, both stick
# models to the exit at Gamma = 1e-3 ... 1e-6, a markdown table.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh" >/dev/null
echo "== $(git -C "$ROOT" rev-parse --short HEAD)$(git -C "$ROOT" diff --quiet HEAD -- src || echo ', modified'), $(nproc) cores"
"$ROOT/build/tribo_bench_rigid_limit"
