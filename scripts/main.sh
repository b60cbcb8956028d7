#!/usr/bin/env bash
# The main job: set up (if needed), then the paper's parameter study through the FMU
# (`tribo study`, the Python package's command) on a local Dask cluster, one worker per core.
#   scripts/main.sh          reduced study (6 roundness values, tau to 1000): out/study/,
#                            under two minutes on 2 cores
#   scripts/main.sh --full   the paper's study (epsilon 0.1..1.0, tau to 5000): out/study-full/
# Other arguments go to `tribo study` (see `tribo study --help`), e.g. --out docs/study,
# --scheduler tcp://host:8786 (an existing Dask cluster), --fresh.
# One run of the paper's case through the C API alone: build/tribo_paper_run.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$ROOT/scripts/setup.sh"
cd "$ROOT"
exec "$ROOT/.venv/bin/tribo" study "$@"
