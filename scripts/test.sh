#!/usr/bin/env bash
# Every test: set up (if needed), then the C unit tests (Release, and again under
# AddressSanitizer + UndefinedBehaviorSanitizer) and the Python tests, with the fuzz suite
# (tests/fuzz: the Release FMUs and the sanitizer build's; a longer campaign is
# scripts/fuzz.sh). 9.5 to 11 minutes on a fresh clone of 2 idle cores (docs/platforms.md).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
TRIBO_SETUP_SANITIZE=1 "$ROOT/scripts/setup.sh"
JOBS=$(nproc)
# The C tests of both builds and the multi-platform FMUs at once (each step's output kept and
# shown in turn), so that one's long tests (test_stability, the parts of test_regression) run
# beside the other's many short ones; then pytest, which needs the FMUs
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
ctest --test-dir "$ROOT/build" --output-on-failure -j "$JOBS" > "$logs/release" 2>&1 &
release=$!
ctest --test-dir "$ROOT/build-sanitize" --output-on-failure -j "$JOBS" > "$logs/sanitize" 2>&1 &
sanitize=$!
"$ROOT/scripts/build_fmus.sh" > "$logs/fmus" 2>&1 &
fmus=$!
failed=0
for step in "release:C unit tests (Release)" \
            "sanitize:C unit tests (AddressSanitizer + UndefinedBehaviorSanitizer)" \
            "fmus:The multi-platform FMUs (Windows binaries, sources/; checked under Wine by pytest)"; do
  name=${step%%:*}
  status=0
  wait "${!name}" || status=$?
  echo "== ${step#*:}"
  cat "$logs/$name"
  if [ "$status" -ne 0 ]; then
    echo "== ${step#*:}: failed (exit $status)"
    failed=1
  fi
done
[ "$failed" -eq 0 ] || exit 1
echo "== Python tests (pytest + fmpy, libcosim, ecos, with the fuzz suite; a worker per core)"
# worksteal: a worker that runs out takes tests still queued on another (with pytest-xdist's
# default, one worker sat idle for the last minute while the other worked through its queue)
"$ROOT/.venv/bin/python" -m pytest -q -n "$JOBS" --dist worksteal "$ROOT/tests/python"
