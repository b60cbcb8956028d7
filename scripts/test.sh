#!/usr/bin/env bash
# Every test: set up (if needed), then the C unit tests (Release, and again under
# AddressSanitizer + UndefinedBehaviorSanitizer) and the Python tests, with the fuzz suite
# (tests/fuzz: the Release FMUs and the sanitizer build's, about two minutes on 2 cores).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
TRIBO_SETUP_SANITIZE=1 "$ROOT/scripts/setup.sh"
JOBS=$(nproc)
echo "== C unit tests (Release)"
ctest --test-dir "$ROOT/build" --output-on-failure -j "$JOBS"
echo "== C unit tests (AddressSanitizer + UndefinedBehaviorSanitizer)"
ctest --test-dir "$ROOT/build-sanitize" --output-on-failure -j "$JOBS"
echo "== The multi-platform FMUs (Windows binaries, sources/; checked under Wine by pytest)"
"$ROOT/scripts/build_fmus.sh"
echo "== Python tests (pytest + fmpy, libcosim, ecos, with the fuzz suite; a worker per core)"
"$ROOT/.venv/bin/python" -m pytest -q -n "$JOBS" "$ROOT/tests/python"
