#!/usr/bin/env bash
# A fuzz campaign: the test suite's fuzz runs (tests/python/test_fuzz.py: every FMU, on the
# Release and the sanitizer builds) with SCALE times their sequences and mutated states, and
# their seeds moved by SEED, so that the sequences are new ones (the test suite repeats its
# fixed seeds as a regression check). A finding fails its test with the sequence's calls;
# each run's counts are in <build>/fuzz/*.json.
# Usage: scripts/fuzz.sh [SCALE=4] [SEED=a number from the clock]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
scale=${1:-4}
seed=${2:-$(date +%s)}
TRIBO_SETUP_SANITIZE=1 "$ROOT/scripts/setup.sh" >/dev/null
echo "fuzz: budgets times $scale, seeds plus $seed"
TRIBO_FUZZ_SCALE=$scale TRIBO_FUZZ_SEED=$seed \
  "$ROOT/.venv/bin/python" -m pytest -q -n "$(nproc)" -rP "$ROOT/tests/python/test_fuzz.py"
