#!/usr/bin/env bash
# Every test: set up (if needed), then the C unit tests (Release, and again under
# AddressSanitizer + UndefinedBehaviorSanitizer) and the Python tests, with the fuzz suite
# (tests/fuzz: the Release FMUs and the sanitizer build's; a longer campaign is
# scripts/fuzz.sh). About 9 minutes on a fresh clone of 2 idle cores, up to a fifth more as the
# machine's speed varies (docs/platforms.md).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
TRIBO_SETUP_SANITIZE=1 "$ROOT/scripts/setup.sh"
JOBS=$(nproc)
# The C tests of both builds and the multi-platform FMUs at once (each step's output kept and
# shown when it ends), so that one's long tests (test_stability, the parts of test_regression)
# run beside the other's many short ones; pytest, which needs the FMUs, once the sanitizer
# build's tests and the FMUs are done, beside the last of the Release tests (one long
# single-process test there would otherwise leave a core idle), not beside the sanitizer
# build's, whose hang guards are sized for the load of the three steps
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
ctest --test-dir "$ROOT/build" --output-on-failure -j "$JOBS" > "$logs/release" 2>&1 &
release=$!
ctest --test-dir "$ROOT/build-sanitize" --output-on-failure -j "$JOBS" > "$logs/sanitize" 2>&1 &
sanitize=$!
"$ROOT/scripts/build_fmus.sh" > "$logs/fmus" 2>&1 &
fmus=$!
failed=0
finished() { # finished <step> <title>: waits for a step started above and shows its output
  local status=0
  wait "${!1}" || status=$?
  echo "== $2"
  cat "$logs/$1"
  if [ "$status" -ne 0 ]; then
    echo "== $2: failed (exit $status)"
    failed=1
  fi
}
finished sanitize "C unit tests (AddressSanitizer + UndefinedBehaviorSanitizer)"
finished fmus "The multi-platform FMUs (Windows binaries, sources/; checked under Wine by pytest)"
if [ "$failed" -eq 0 ]; then
  echo "== Python tests (pytest + fmpy, libcosim, ecos, with the fuzz suite; a worker per core)"
  # worksteal: a worker that runs out takes tests still queued on another (with
  # pytest-xdist's default, one worker sat idle for the last minute while the other worked
  # through its queue)
  "$ROOT/.venv/bin/python" -m pytest -q -n "$JOBS" --dist worksteal "$ROOT/tests/python" ||
    failed=1
fi
finished release "C unit tests (Release)"
exit "$failed"
