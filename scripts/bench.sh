#!/usr/bin/env bash
# Benchmark (not a test): cost of each charge model on the paper's case.
# Arguments go to the benchmark: t_end=1000 rounds=1.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh"
exec "$ROOT/build/tribo_bench_charge_models" "$@"
