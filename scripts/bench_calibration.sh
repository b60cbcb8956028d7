#!/usr/bin/env bash
# The calibration benchmark: `tribo calibrate` of PE on steel against 20 single impacts and
# 3 chute runs (50 grains each, the reference case's feed) made by the model itself at
# sigma0 = -1.5e-5 C/m2 with complete transfer and 0.05 decades of noise (bench/calibration_data.py),
# on a local Dask cluster of WORKERS threads: its wall time (the cluster's start included),
# the model runs it made, and the sigma0 it found. Usage:
# scripts/bench_calibration.sh [WORKERS] (default 2); the data in out/bench_calibration/.
set -euo pipefail
cd "$(dirname "$0")/.."
workers=${1:-2}
dir=out/bench_calibration
mkdir -p "$dir"
.venv/bin/python bench/calibration_data.py "$dir"
out=$dir/workers-$workers
rm -rf "$out"  # a new folder each time
start=$(date +%s.%N)
.venv/bin/tribo calibrate --impacts "$dir/impacts.csv" --chutes "$dir/chutes.csv" \
  --workers "$workers" --out "$out" --no-progress > "$out.log" 2>&1 || { cat "$out.log"; exit 1; }
end=$(date +%s.%N)
cat "$out.log"
.venv/bin/python -c "import sys; print(f'{sys.argv[1]} worker(s): {float(sys.argv[3]) - float(sys.argv[2]):.1f} s wall, the command from start to end')" \
  "$workers" "$start" "$end"
