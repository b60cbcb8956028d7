#!/usr/bin/env bash
# What the sampling and the charging cost on a feeder (issue 44, docs/dem.md "What it
# costs"): 40 PE spheres of 0.6-1 mm (seed 1, dilute) on a level feeder 5 cm long (0.5 mm
# at 50 Hz along a stroke at 30 degrees), `tribo dem` once (LIGGGHTS' CPU and the
# charging's, which reads the contacts' output and charges it); then its LIGGGHTS input
# again with and without the contacts' output (its dump, the variables and compute it
# alone uses), BENCH_ROUNDS times each (default 5), alternately: the least CPU of each and
# their medians. BENCH_ALSO=FOLDER runs that folder's in.liggghts (with its STL files)
# alternately with them too (an input written by another revision, to compare in one run).
# Results: out/bench-dem-sampling/ (BENCH_OUT).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PY=${PYTHON:-"$ROOT/.venv/bin/python"}
OUT=${BENCH_OUT:-"$ROOT/out/bench-dem-sampling"}
ROUNDS=${BENCH_ROUNDS:-5}
ALSO=${BENCH_ALSO:+$(cd "$BENCH_ALSO" && pwd)}
mkdir -p "$OUT"
cd "$OUT"
"$PY" -m tribo dem -n 40 --seed 1 --epsilon 1 --size uniform:6e-4:1e-3 --stiffness-scale 0.01 \
  --vibration 5e-4,50,30 --tilt-deg 0 --chute-length 0.05 --maps "$OUT/maps" --no-progress \
  --no-plot --out dem --fresh | grep "CPU:"
variants=(with without)
rm -rf with without also && cp -r dem/liggghts with && cp -r dem/liggghts without
grep -v "contacts\|variable written\|variable wall\|compute radius" dem/liggghts/in.liggghts > without/in.liggghts
if [[ -n $ALSO ]]; then
  mkdir also && cp "$ALSO"/in.liggghts "$ALSO"/*.stl also/ && variants+=(also)
fi
for d in "${variants[@]}"; do rm -f "$d"/*.dump "$d"/cpu.txt "$d"/restart*; done
for k in $(seq "$ROUNDS"); do
  for d in "${variants[@]}"; do
    ( cd "$d" && rm -f ./*.dump && /usr/bin/time -f "%U %S" -a -o cpu.txt liggghts -in in.liggghts \
        -log log.liggghts -echo none > /dev/null )
  done
done
"$PY" - "${variants[@]}" <<'PYEOF'
import json, statistics, sys
cpu = {v: sorted(sum(map(float, line.split())) for line in open(f"{v}/cpu.txt") if line.strip())
       for v in sys.argv[1:]}
meta = json.load(open("dem/population.json"))
frames = sum(line.startswith(b"ITEM: TIMESTEP") for line in open("with/contacts.dump", "rb"))
print(f"tribo dem: LIGGGHTS {meta['dem_cpu_s']:.3g} s of CPU, the charging {meta['charging_cpu_s']:.3g} s "
      f"({100 * meta['charging_cpu_s'] / meta['dem_cpu_s']:.3g} %); contacts.dump: {frames} frames")
for v, c in cpu.items():
    print(f"{v}: " + " ".join(f"{x:.3g}" for x in c) + " s")
w, wo = cpu["with"], cpu["without"]
print(f"the sampling: +{100 * (w[0] / wo[0] - 1):.3g} % of LIGGGHTS' CPU (the least of each), "
      f"+{100 * (statistics.median(w) / statistics.median(wo) - 1):.3g} % (the medians)")
if "also" in cpu:
    print(f"BENCH_ALSO's input: +{100 * (cpu['also'][0] / wo[0] - 1):.3g} % over the input without "
          f"the contacts' output (the least of each)")
PYEOF
