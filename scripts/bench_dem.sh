#!/usr/bin/env bash
# tribo dem's costs (docs/dem.md), each measured in this one run on this machine:
#  1. the dilute limit: LIGGGHTS' CPU with the contacts' output, the same input without it
#     (what the sampling costs), and the charging's CPU (reading the outputs, the map
#     lookups; the maps made beforehand, once);
#  2. the project's own population of the same grains and chute: its CPU per grain against
#     the DEM-coupled run's;
#  3. a fed stream on 2 MPI ranks (grains meet): the whole coupled run, wall and CPU, and
#     the figure of its q/m against the dilute limit's (copied to docs/dem/dilute_vs_fed.png).
# Sizes: BENCH_DILUTE (default 40) and BENCH_FED (default 100) grains of 0.6-1 mm PE
# spheres on the 0.3 m steel chute at 30 degrees, the fed ones dropped from 5-15 mm at
# BENCH_RATE grains/s (default 100) in 5 lanes, and the same grains in the dilute limit;
# LIGGGHTS' moduli at BENCH_STIFFNESS (default 0.01) of PE's and
# steel's. Results: out/bench-dem/ (kept between runs: the maps in out/bench-dem/maps).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PY="$ROOT/.venv/bin/python"
TRIBO="$ROOT/.venv/bin/tribo"
OUT=${BENCH_OUT:-"$ROOT/out/bench-dem"}
N=${BENCH_DILUTE:-40}
NF=${BENCH_FED:-100}
RATE=${BENCH_RATE:-100}
STIFF=${BENCH_STIFFNESS:-0.01}
FEED=(--epsilon 1 --size uniform:6e-4:1e-3 --stiffness-scale "$STIFF" --maps "$OUT/maps" --no-progress)
# the fed stream's grains drop from heights 5-15 mm: their bounces differ, so that they meet
DROPS=(--drop-height uniform:0.005:0.015)
mkdir -p "$OUT"
cd "$OUT"

"$TRIBO" dem -n "$N" --seed 1 "${FEED[@]}" --out dilute --fresh | sed -n 2p
# the sampling's cost: the dilute run's LIGGGHTS input again, with and without the
# contacts' output (its dump lines removed), four times each, alternately; the least CPU of each
rm -rf withdump nodump && cp -r dilute/liggghts withdump && cp -r dilute/liggghts nodump
rm -f withdump/*.dump nodump/*.dump
grep -v "contacts\|variable written\|variable wall\|compute radius" dilute/liggghts/in.liggghts > nodump/in.liggghts
for k in 1 2 3 4; do
  for d in withdump nodump; do
    ( cd "$d" && /usr/bin/time -f "%U %S" -a -o cpu.txt liggghts -in in.liggghts -log log.liggghts -echo none > /dev/null )
  done
done
"$PY" -m tribo population -n "$N" --seed 1 --epsilon 1 --size uniform:6e-4:1e-3 --serial \
  --no-progress --no-plot --out population --fresh > /dev/null
"$TRIBO" dem -n "$NF" --seed 2 "${FEED[@]}" "${DROPS[@]}" --out fed-dilute --fresh --no-plot | sed -n 2p
/usr/bin/time -f "%e s wall" -o fed.time "$TRIBO" dem -n "$NF" --seed 2 "${FEED[@]}" "${DROPS[@]}" \
  --feed-rate "$RATE" --lanes 5 --ranks 2 --out fed --fresh | sed -n 2p

"$PY" - "$N" "$NF" "$RATE" <<'PYEOF'
import json, sys
import pandas as pd
from tribo.dem.plot import write_comparison_figure
n, nf, rate = int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3])
meta = json.load(open("dilute/population.json"))
dem, charging = meta["dem_cpu_s"], meta["charging_cpu_s"]
def least(path):
    return min(sum(map(float, line.split())) for line in open(path) if line.strip())
with_dump, without = least("withdump/cpu.txt"), least("nodump/cpu.txt")
pop = pd.read_csv("population/particles.csv")
pop_cpu = pop["cpu_s"].sum() / n
print(f"dilute, {n} grains, 1 rank: LIGGGHTS CPU {dem:.3g} s in the coupled run; the same "
      f"input, least of four: {with_dump:.3g} s with the contacts' output, {without:.3g} s "
      f"without it (the sampling: {100 * (with_dump / without - 1):.3g} %); charging "
      f"{charging:.3g} s = {100 * charging / dem:.3g} % of LIGGGHTS'")
print(f"per grain: the population {pop_cpu:.3g} s CPU, LIGGGHTS + charging "
      f"{(dem + charging) / n:.3g} s: the population is {(dem + charging) / n / pop_cpu:.3g} "
      f"times cheaper")
fed = json.load(open("fed/population.json"))
wall = open("fed.time").read().split()[0]
print(f"fed stream, {nf} grains at {rate:g}/s, 2 ranks: {wall} s wall, LIGGGHTS CPU "
      f"{fed['dem_cpu_s']:.3g} s (both ranks), charging {fed['charging_cpu_s']:.3g} s")
a, b = pd.read_csv("fed-dilute/particles.csv"), pd.read_csv("fed/particles.csv")
for name, rows in (("dilute", a), ("fed", b)):
    left = rows[rows.exited == 1]
    qm = left.charge_static.sum() / (left["size"] ** 3 * left["density"]).sum() / (3.141592653589793 / 6)
    print(f"{name}: q/m mean {rows.charge_to_mass_static.mean() * 1e6:.4g} uC/kg, stream "
          f"{qm * 1e6:.4g} uC/kg, impacts per grain {rows.impacts.mean():.3g}")
write_comparison_figure(a, b, "dilute_vs_fed.png",
                        title=f"{nf} PE spheres of 0.6-1 mm dropped from 5-15 mm onto 0.3 m of "
                              f"steel at 30°: dilute limit vs fed at {rate:g} grains/s in 5 "
                              f"lanes (LIGGGHTS)")
PYEOF
mkdir -p "$ROOT/docs/dem" && cp dilute_vs_fed.png "$ROOT/docs/dem/"
