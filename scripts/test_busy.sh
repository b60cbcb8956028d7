#!/usr/bin/env bash
# The test command on a busy machine (docs/platforms.md): .ci/run with one CPU-bound job per
# core beside it for its whole length, as another developer's build or test suite would be.
# The tests assert behaviour and bound work, not time, so they pass there; it prints the
# wall time the run took.
# Usage: scripts/test_busy.sh   (on a fresh clone: git clone <repository> && cd <clone>)
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
busy=()
stop_busy() {
  # only the jobs started here, by their process ids
  ((${#busy[@]})) && kill "${busy[@]}" 2>/dev/null || true
}
trap stop_busy EXIT
for _ in $(seq "$(nproc)"); do
  yes > /dev/null &
  busy+=($!)
done
echo "test_busy: ${#busy[@]} busy jobs (yes > /dev/null) beside .ci/run, $(nproc) cores"
start=$(date +%s)
"$ROOT/.ci/run"
echo "test_busy: .ci/run passed in $(($(date +%s) - start)) s of wall time beside ${#busy[@]} busy jobs"
