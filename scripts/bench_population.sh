#!/usr/bin/env bash
# The population benchmark: 1000 particles of the SI reference case's feed
# (epsilon 0.3-1, sizes 0.2-2 mm, random orientation; PE on 0.3 m of steel at 30 degrees)
# through `tribo population` on a local Dask cluster of 1 and of 2 workers: wall time and
# CPU time per particle. Usage: scripts/bench_population.sh [N] [WORKERS...]; more options
# of `tribo population` in $TRIBO_POPULATION_OPTIONS (e.g. --processes: worker processes, not
# the local cluster's threads).
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-1000}
shift || true
workers=("${@:-1 2}")
for w in ${workers[@]}; do
  out=out/bench_population/workers-$w
  # a new folder each time: every particle runs (the same folder would resume); its parent
  # holds the log
  rm -rf "$out"
  mkdir -p "$(dirname "$out")"
  start=$(date +%s.%N)
  .venv/bin/tribo population -n "$n" --seed 1 --workers "$w" --out "$out" --no-progress --no-plot ${TRIBO_POPULATION_OPTIONS:-} > "$out.log" 2>&1 \
    || { cat "$out.log"; exit 1; }
  end=$(date +%s.%N)
  .venv/bin/python - "$out/particles.csv" "$n" "$w" "$start" "$end" <<'PY'
import sys
import pandas as pd
path, n, w, start, end = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
df = pd.read_csv(path)
wall = end - start
print(f"{w} worker(s): {len(df)} of {n} particles in {wall:.1f} s wall (cluster start included), "
      f"{wall / len(df) * 1e3:.1f} ms wall per particle; CPU per particle (the run's thread): "
      f"mean {df.cpu_s.mean() * 1e3:.1f} ms, median {df.cpu_s.median() * 1e3:.1f} ms, "
      f"max {df.cpu_s.max():.2f} s; exited {int(df.exited.sum())}")
PY
done
