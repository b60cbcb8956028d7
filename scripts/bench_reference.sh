#!/usr/bin/env bash
# The SI reference case measured (bench/reference_case.c; the numbers of
# docs/reference_case.md): CVODE to the chute's exit, its spread with the tolerances, and the
# fixed step's estimated cost. Arguments go to the benchmark: rounds=3 slice=2 "name=value ...".
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh" >/dev/null
exec "$ROOT/build/tribo_reference_case" "$@"
