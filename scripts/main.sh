#!/usr/bin/env bash
# The main job: set up (if needed), then run the paper's low-friction case at
# epsilon = 0.5 to tau = 1000 through the C API. Extra arguments (name=value) go to
# the run, e.g. scripts/main.sh epsilon=0.3 mu=1 nu=1.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh"
exec "$ROOT/build/tribo_paper_run" "$@"
