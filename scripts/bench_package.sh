#!/usr/bin/env bash
# What the Python package costs beside the core it drives (bench/package_overhead.py;
# docs/populations.md, "Benchmark"): per grain of the population benchmark's feed and for
# the rolling 1 mm disc through tribo.run_si, the package's CPU time and the core's own in
# the same process (the disc's also reading the same rows; the whole population command
# against the core: scripts/bench_population_package.sh). With --before REV the package of revision REV (its python/tribo, on
# the same build's FMUs) is measured too, in rounds that alternate with this tree's, each a
# fresh process, so that one run of this command gives the before and the after under the
# same load; the table gives each quantity's median over the rounds and the ratio.
# Usage: scripts/bench_package.sh [--before REV] [rounds=3] [grains=100]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
rounds=${1:-3}
grains=${2:-100}
"$ROOT/scripts/setup.sh" >/dev/null
export TRIBO_BUILD_DIR="$ROOT/build"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
before_package "$tmp"
for ((r = 1; r <= rounds; r++)); do
  if [ -n "$before" ]; then
    PYTHONPATH="$tmp/before/python" "$ROOT/.venv/bin/python" "$ROOT/bench/package_overhead.py" \
      --grains "$grains" --label before >> "$tmp/results.jsonl"
  fi
  PYTHONPATH="$ROOT/python" "$ROOT/.venv/bin/python" "$ROOT/bench/package_overhead.py" \
    --grains "$grains" --label after >> "$tmp/results.jsonl"
done
"$ROOT/.venv/bin/python" - "$tmp/results.jsonl" "${before:+$(git -C "$ROOT" rev-parse --short "$before")}" \
  "$(tree_label python)" <<'PY'
import json
import sys
import numpy as np
rows = [json.loads(line) for line in open(sys.argv[1])]
labels = [l for l in ("before", "after") if any(r["label"] == l for r in rows)]
names = {"before": f"before ({sys.argv[2]})", "after": f"this tree ({sys.argv[3]})"}
quantities = [
    ("grain: the package's CPU, mean [ms]", lambda r: r["grain_package_ms"]),
    ("grain: the core's own CPU, mean [ms]", lambda r: r["grain_core_ms"]),
    ("grain: the package's overhead, mean [ms]", lambda r: r["grain_overhead_ms"]),
    ("grain: the package's overhead, median [ms]", lambda r: r["grain_overhead_median_ms"]),
    ("disc: the core's own CPU [s]", lambda r: r["disc"]["core_s"]),
    ("disc: the core, stepped to every 0.1 ms, nothing read [s]", lambda r: r["disc"]["core_points_s"]),
    ("disc: the core, the same rows read in blocks [s]", lambda r: r["disc"]["core_rows_s"]),
    ("disc: tribo.run_si, rows every 0.1 ms [s]", lambda r: r["disc"]["run_si_s"]),
    ("disc: tribo.run_si, the end alone [s]", lambda r: r["disc"]["run_si_end_s"]),
]
n = {l: sum(r["label"] == l for r in rows) for l in labels}
print(f"{rows[0]['grains']} grains of the population benchmark's feed; medians of "
      + ", ".join(f"{n[l]} rounds {names[l]}" for l in labels))
print()
print("| quantity | " + " | ".join(names[l] for l in labels)
      + (" | after / before |" if len(labels) == 2 else " |"))
print("|---|" + "---|" * (len(labels) + (len(labels) == 2)))
for title, get in quantities:
    values = {}
    for l in labels:
        xs = [get(r) for r in rows if r["label"] == l and get(r) is not None]
        values[l] = float(np.median(xs)) if xs else None
    cells = [f"{values[l]:.4g}" if values[l] is not None else "n/a" for l in labels]
    if len(labels) == 2:
        a, b = values["before"], values["after"]
        cells.append(f"{b / a:.3g}" if a and b is not None else "")
    print(f"| {title} | " + " | ".join(cells) + " |")
rolls = [r["disc"] for r in rows if r["label"] == "after"]
print()
print(f"the disc's rows: {rolls[0]['rows']}; this tree's run_si against the core: rows every "
      f"0.1 ms {np.median([d['run_si_s'] / d['core_rows_s'] for d in rolls]):.2f}x the core's "
      f"same run and rows ({np.median([d['run_si_s'] / d['core_s'] for d in rolls]):.2f}x its run "
      f"to the exit in one step), the end alone "
      f"{np.median([d['run_si_end_s'] / d['core_s'] for d in rolls]):.2f}x (medians of the rounds' ratios)")
PY
