#!/usr/bin/env bash
# The population benchmark: 1000 particles of the SI reference case's feed
# (epsilon 0.3-1, sizes 0.2-2 mm, random orientation; PE on 0.3 m of steel at 30 degrees)
# through `tribo population` on a local Dask cluster of 1 and of 2 workers: wall time and
# CPU time per particle. Usage: scripts/bench_population.sh [N] [WORKERS...]; more options
# of `tribo population` in $TRIBO_POPULATION_OPTIONS (e.g. --processes: worker processes, not
# the local cluster's threads; --set mu=0.5; --epsilon 1). With --before REV the package of
# revision REV (its python/tribo, on this build's FMUs) runs each benchmark first, then this
# tree's, so that one run of this command gives the before and the after under the same
# load, and the particles' rows are compared (every column but the CPU and wall times).
# Usage: scripts/bench_population.sh [--before REV] [N] [WORKERS...]
set -euo pipefail
cd "$(dirname "$0")/.."
before=""
if [ "${1:-}" = --before ]; then
  before=${2:?"--before needs a revision"}
  shift 2
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  git archive "$before" python/tribo | tar -x -C "$tmp"
  # the FMUs this tree's package finds, for the other package (which is not in a checkout)
  TRIBO_BUILD_DIR=$(.venv/bin/python -c "from tribo.fmu.locate import build_dir; print(build_dir())")
  export TRIBO_BUILD_DIR
fi
n=${1:-1000}
shift || true
workers=("${@:-1 2}")
run() { # run <label> <out> <workers> [PYTHONPATH]: one population, its line
  local label=$1 out=$2 w=$3 start end command=(.venv/bin/tribo)
  [ -z "${4:-}" ] || command=(env PYTHONPATH="$4" .venv/bin/python -m tribo)
  # a new folder each time: every particle runs (the same folder would resume); its parent
  # holds the log
  rm -rf "$out"
  mkdir -p "$(dirname "$out")"
  start=$(date +%s.%N)
  # a run that fails is counted (the command says so and exits 1); anything else stops here
  "${command[@]}" population -n "$n" --seed 1 --workers "$w" --out "$out" --no-progress --no-plot ${TRIBO_POPULATION_OPTIONS:-} > "$out.log" 2>&1 \
    || grep -q "failed; .* done$" "$out.log" || { cat "$out.log"; exit 1; }
  end=$(date +%s.%N)
  .venv/bin/python - "$out/particles.csv" "$n" "$w" "$start" "$end" "$label" <<'PY'
import sys
import pandas as pd
path, n, w, start, end, label = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5]), sys.argv[6]
df = pd.read_csv(path)
wall = end - start
print(f"{label}{w} worker(s): {len(df)} of {n} particles in {wall:.1f} s wall (cluster start included), "
      f"{wall / len(df) * 1e3:.1f} ms wall per particle; CPU per particle (the run's thread): "
      f"mean {df.cpu_s.mean() * 1e3:.1f} ms, median {df.cpu_s.median() * 1e3:.1f} ms, "
      f"max {df.cpu_s.max():.2f} s, total {df.cpu_s.sum():.1f} s; exited {int(df.exited.sum())}"
      + (f"; {n - len(df)} failed" if len(df) < n else ""))
PY
}
for w in ${workers[@]}; do
  out=out/bench_population/workers-$w
  if [ -n "$before" ]; then
    run "before ($(git rev-parse --short "$before")), " "$out-before" "$w" "$tmp/python"
    run "this tree, " "$out" "$w"
    .venv/bin/python - "$out-before/particles.csv" "$out/particles.csv" <<'PY'
import sys
import pandas as pd
timing = ["cpu_s", "wall_s"]
a, b = (pd.read_csv(p, dtype=str).drop(columns=timing).sort_values("key", ignore_index=True)
        for p in sys.argv[1:])
print("  the particles' rows (all but the CPU and wall times): "
      + ("identical" if a.equals(b) else "DIFFER"))
PY
  else
    run "" "$out" "$w"
  fi
done
