#!/usr/bin/env bash
# What the sampling and the charging cost on a feeder (issue 44, docs/dem.md "What it
# costs"): 40 PE spheres of 0.6-1 mm (seed 1, dilute) on a level feeder 5 cm long (0.5 mm
# at 50 Hz along a stroke at 30 degrees), `tribo dem` once (LIGGGHTS' CPU and the
# charging's, which reads the contacts' output and charges it); then its LIGGGHTS input
# again with and without the contacts' output (its dump, the variables and compute it
# alone uses), BENCH_ROUNDS times each (default 5), alternately: the least CPU of each,
# their medians, and the median of each round's ratio (paired: a round's runs share the
# machine's load); the sampling and the charging together, the issue's number. --before REV:
# the same `tribo dem` command by revision REV's package too (its LIGGGHTS run and its
# charging), its input run alternately with the others (`also`). BENCH_ALSO=FOLDER instead
# runs that folder's in.liggghts (with its STL files) alternately with them (an input
# written by another revision). Results: out/bench-dem-sampling/ (BENCH_OUT).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
PY=${PYTHON:-"$ROOT/.venv/bin/python"}
OUT=${BENCH_OUT:-"$ROOT/out/bench-dem-sampling"}
ROUNDS=${BENCH_ROUNDS:-5}
ALSO=${BENCH_ALSO:+$(cd "$BENCH_ALSO" && pwd)}
mkdir -p "$OUT"
# the FMUs this checkout built, for the revision before's package too
export TRIBO_BUILD_DIR=${TRIBO_BUILD_DIR:-"$ROOT/build"}
cd "$OUT"
feeder=(dem -n 40 --seed 1 --epsilon 1 --size uniform:6e-4:1e-3 --stiffness-scale 0.01
        --vibration 5e-4,50,30 --tilt-deg 0 --chute-length 0.05 --maps "$OUT/maps" --no-progress
        --no-plot --fresh)
said=$("$PY" -m tribo "${feeder[@]}" --out dem | grep "CPU:")
echo "this tree ($(tree_label python/tribo/dem)): $said"
if [ -n "$before" ]; then
  rm -rf before && before_package "$OUT"
  said=$(PYTHONPATH="$OUT/before/python" "$PY" -m tribo "${feeder[@]}" --out before_dem | grep "CPU:")
  echo "$before: $said"
  ALSO=$OUT/before_dem/liggghts
fi
variants=(with without)
rm -rf with without also && cp -r dem/liggghts with && cp -r dem/liggghts without
grep -v "contacts\|variable written" dem/liggghts/in.liggghts > without/in.liggghts
if [[ -n $ALSO ]]; then
  mkdir also
  cp "$ALSO"/in.liggghts "$ALSO"/*.stl also/
  variants+=(also)
fi
# BENCH_SAMPLE_EVERY=N: every input's contacts written every N steps instead, its run cut
# to BENCH_PIECES pieces (default 20, a quarter of it): a sample's cost, many times over,
# the inputs' formulas compared at one interval
if [[ -n ${BENCH_SAMPLE_EVERY:-} ]]; then
  for d in "${variants[@]}"; do
    sed -i -e "s/^\(dump contacts all custom \)[0-9]* /\1$BENCH_SAMPLE_EVERY /" \
      -e "s/^variable piece loop .*/variable piece loop ${BENCH_PIECES:-20}/" "$d/in.liggghts"
  done
fi
for d in "${variants[@]}"; do rm -f "$d"/*.dump "$d"/cpu.txt "$d"/restart*; done
for k in $(seq "$ROUNDS"); do
  for d in "${variants[@]}"; do
    ( cd "$d" && rm -f ./*.dump && /usr/bin/time -f "%U %S" -a -o cpu.txt liggghts -in in.liggghts \
        -log log.liggghts -echo none > /dev/null )
  done
done
BEFORE_DEM=${before:+before_dem} SAMPLE_EVERY=${BENCH_SAMPLE_EVERY:-} "$PY" - "${variants[@]}" <<'PYEOF'
import json, os, statistics, sys
# each run's CPU in the order run (rounds alternate: the same load for a round's inputs)
runs = {v: [sum(map(float, line.split())) for line in open(f"{v}/cpu.txt") if line.strip()]
        for v in sys.argv[1:]}
cpu = {v: sorted(c) for v, c in runs.items()}
wo = cpu["without"]
frames = sum(line.startswith(b"ITEM: TIMESTEP") for line in open("with/contacts.dump", "rb"))


def said(name, folder, variant):
    """The sampling of `variant`'s input and the charging of its tribo dem run (folder's
    population.json, where there is one): each, and together, in % of LIGGGHTS' CPU: the
    least of each, their medians, and the median of each round's ratio to the round's run
    without the contacts' output (paired)."""
    least = 100 * (cpu[variant][0] / wo[0] - 1)
    median = 100 * (statistics.median(cpu[variant]) / statistics.median(wo) - 1)
    paired = 100 * (statistics.median(a / b for a, b in zip(runs[variant], runs["without"])) - 1)
    line = (f"{name}: the sampling +{least:.3g} % of LIGGGHTS' CPU (the least of each), "
            f"+{median:.3g} % (the medians), +{paired:.3g} % (paired)")
    path = f"{folder}/population.json"
    if os.environ["SAMPLE_EVERY"]:  # not the run tribo dem charged: a sample's cost
        each = (statistics.median(cpu[variant]) - statistics.median(wo)) / frames
        line += f"; a sample {1e6 * each:.3g} us of CPU (the medians' over {frames} frames)"
    elif os.path.exists(path):
        meta = json.load(open(path))
        charging = 100 * meta["charging_cpu_s"] / meta["dem_cpu_s"]
        line += (f"; the charging {charging:.3g} % ({meta['charging_cpu_s']:.3g} s of "
                 f"{meta['dem_cpu_s']:.3g} s); together {least + charging:.3g} % (the least), "
                 f"{median + charging:.3g} % (the medians), {paired + charging:.3g} % (paired)")
    print(line)


print(f"contacts.dump: {frames} frames")
for v, c in cpu.items():
    print(f"{v}: " + " ".join(f"{x:.3g}" for x in c) + " s")
said("this tree", "dem", "with")
if "also" in cpu:
    said(os.environ["BEFORE_DEM"] and "the revision before" or "the other input",
         os.environ["BEFORE_DEM"] or "-", "also")
PYEOF
