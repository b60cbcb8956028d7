#!/usr/bin/env bash
# Work-precision report (not a test): the paper's fixed step against CVODE, error against
# CPU time. Writes docs/work_precision.{md,png,csv} and docs/work_precision_horizon.png.
# Takes about two minutes on 2 cores.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh"
exec "$ROOT/.venv/bin/python" "$ROOT/examples/work_precision.py" --build "$ROOT/build" --out "$ROOT/docs" "$@"
