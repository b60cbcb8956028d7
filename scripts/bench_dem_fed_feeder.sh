#!/usr/bin/env bash
# The fed feeder against the dilute one (issue 44, docs/dem.md "The fed feeder"): the same
# sphere feed (epsilon 1, PE of 0.6-1 mm on steel, seed 1) through the same vibratory feeder
# (a level plate BENCH_LENGTH long, default 0.3 m, moved 0.5 mm at 50 Hz along a stroke at 30
# degrees to it) in LIGGGHTS, once dilute (a lane each: the grains do not meet) and once fed
# at BENCH_RATE grains/s (default 50) into BENCH_LANES lanes (default 5), where they meet,
# each run once here. Prints, for each: the grains that left by the end, the conveying speed
# (the plate's length over the mean time from a grain's drop to its exit), the impacts per
# grain on the plate and on the side walls, the stream's mass-weighted q/m and its spread,
# the impacts a second and the q/m per impact, LIGGGHTS' and the charging's CPU; grain by
# grain (the same draw: the same grains in the same order) the fed over the dilute q/m,
# impacts and time on the plate; writes summary.md (the table), compare.csv (a row per
# grain) and fed_feeder.png into out/bench-dem-fed-feeder/ (BENCH_OUT), the figure copied to
# docs/dem/.
#
# BENCH_BACK=D (m) runs the fed stream a third time with the plate and its back wall D
# further behind the drop points (the back wall's part in the fed stream's speed).
#
# Needs LIGGGHTS (scripts/setup.sh). Sizes: BENCH_GRAINS (default 150), BENCH_T_END
# (default 20 s: a grain crosses 0.3 m in some 6 s), BENCH_STIFFNESS (default 0.01:
# LIGGGHTS' moduli, docs/dem.md). BENCH_REPORT_ONLY=1 makes the table and the figure again
# from the runs already in BENCH_OUT.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PY=${PYTHON:-"$ROOT/.venv/bin/python"}
OUT=${BENCH_OUT:-"$ROOT/out/bench-dem-fed-feeder"}
N=${BENCH_GRAINS:-150}
LENGTH=${BENCH_LENGTH:-0.3}
RATE=${BENCH_RATE:-50}
LANES=${BENCH_LANES:-5}
T_END=${BENCH_T_END:-20}
STIFF=${BENCH_STIFFNESS:-0.01}
FEED=(-n "$N" --seed 1 --epsilon 1 --size uniform:6e-4:1e-3 --chute-length "$LENGTH"
      --tilt-deg 0 --vibration 5e-4,50,30 --t-end "$T_END" --stiffness-scale "$STIFF"
      --maps "$OUT/maps" --no-progress --no-plot)
mkdir -p "$OUT"
cd "$OUT"
if [[ ${BENCH_REPORT_ONLY:-0} != 1 ]]; then
  "$PY" -m tribo dem "${FEED[@]}" --out dilute --fresh | grep "CPU:"
  "$PY" -m tribo dem "${FEED[@]}" --feed-rate "$RATE" --lanes "$LANES" --out fed --fresh | grep "CPU:"
  if [[ -n ${BENCH_BACK:-} ]]; then
    "$PY" - "$BENCH_BACK" "${FEED[@]}" --feed-rate "$RATE" --lanes "$LANES" --out fed-back --fresh <<'PYEOF' | grep "CPU:"
import sys
from tribo.cli.main import main
from tribo.dem.device import Chute
start, back = Chute.start, float(sys.argv[1])
Chute.start = lambda self, biggest: start(self, biggest) - back  # the plate begins further back
sys.exit(main(["dem"] + sys.argv[2:]))
PYEOF
  fi
fi
"$PY" - "$N" "$LENGTH" "$RATE" "$LANES" <<'PYEOF'
import json, os, sys
import numpy as np
import pandas as pd
from tribo.plotting import plt, save
from tribo.populations.summary import grain_mass, stream_statistics
from tribo.study.tables import markdown_table
n, length, rate, lanes = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
runs = {"dilute (a lane each)": "dilute", f"fed, {rate:g} grains/s in {lanes} lanes": "fed"}
if os.path.exists("fed-back/particles.csv"):
    runs["the same, the back wall further behind (BENCH_BACK)"] = "fed-back"
data = {k: pd.read_csv(f"{v}/particles.csv") for k, v in runs.items()}
a, b = data["dilute (a lane each)"], data[f"fed, {rate:g} grains/s in {lanes} lanes"]
for c in ("size", "drop_height", "key"):  # the same draw: the same grains in the same order
    assert (a[c] == b[c]).all(), c
entry = {"dilute": np.zeros(n), "fed": np.arange(n) / rate,  # when each grain is dropped
         "fed-back": np.arange(n) / rate}
rows, stay = [], {}
for name, folder in runs.items():
    d, meta = data[name], json.load(open(f"{folder}/population.json"))
    stay[folder] = d["exit_time"] - entry[folder]
    left = d[d.exited == 1]
    qm = left["charge_to_mass_static"]
    stream = stream_statistics(d["charge_to_mass_static"], grain_mass(d), d["exited"])
    rows.append({"run": name, "left": f"{len(left)}/{n}",
                 "conveying speed (m/s)": length / stay[folder][d.exited == 1].mean(),
                 "impacts per grain": d["impacts"].mean(),
                 "side-wall impacts per grain": d["side_impacts"].mean(),
                 "impacts per second": (left["impacts"] / stay[folder][d.exited == 1]).mean(),
                 "q/m per impact (nC/kg)": (qm / left["impacts"]).mean() * 1e9,
                 "stream q/m (uC/kg)": stream["stream_mean"] * 1e6,
                 "spread (uC/kg)": stream["stream_std"] * 1e6,
                 "LIGGGHTS CPU (s)": meta["dem_cpu_s"], "charging CPU (s)": meta["charging_cpu_s"]})
table = pd.DataFrame(rows)
with open("summary.md", "w") as f:
    f.write(markdown_table(table, {c: ".4g" for c in table.columns[2:]}) + "\n")
print(table.to_string(index=False))
both = (a.exited == 1) & (b.exited == 1)
compare = pd.DataFrame({"size": a["size"], "qm_dilute": a["charge_to_mass_static"],
                        "qm_fed": b["charge_to_mass_static"], "impacts_dilute": a["impacts"],
                        "impacts_fed": b["impacts"], "side_impacts_fed": b["side_impacts"],
                        "time_dilute": stay["dilute"], "time_fed": stay["fed"],
                        "both_left": both.astype(int)})
compare.to_csv("compare.csv", index=False)
for what, x, y in (("q/m", "qm_fed", "qm_dilute"), ("impacts", "impacts_fed", "impacts_dilute"),
                   ("time on the feeder", "time_fed", "time_dilute")):
    r = (compare[x] / compare[y])[both]
    print(f"grain by grain ({int(both.sum())} grains that left both ways), fed / dilute {what}: "
          f"{r.mean():.3g} +- {r.std():.2g} (range {r.min():.3g} to {r.max():.3g})")
# each grain's own conveying speed, and its forward spin at the exit (omega r, the model's
# sign reversed: positive rolling forward) where the fast ones differ
for name, folder in runs.items():
    d = data[name]
    speed = length / stay[folder]
    fast = speed > 0.1
    print(f"{name}: the grains' speeds (m/s), 5/25/50/75/95 %: "
          + " ".join(f"{v:.3g}" for v in np.nanpercentile(speed, [5, 25, 50, 75, 95]))
          + f"; {int(fast.sum())} above 0.1 m/s, their exit velocity {d.u[fast].mean():.3g} m/s "
          f"and spin {(-d.omega * d['size'] / 2)[fast].mean():.3g} m/s (the others' "
          f"{d.u[~fast].mean():.3g} and {(-d.omega * d['size'] / 2)[~fast].mean():.3g})")
qpi = (compare.qm_fed / compare.impacts_fed) / (compare.qm_dilute / compare.impacts_dilute)
print(f"q/m per impact, fed / dilute: {qpi[both].mean():.3g} +- {qpi[both].std():.2g}")
fig, (p, q, r) = plt.subplots(1, 3, figsize=(16, 5), layout="constrained")
for ax, x, y, label in ((p, "qm_dilute", "qm_fed", "−q/m (µC/kg)"),
                        (q, "impacts_dilute", "impacts_fed", "impacts on the plate"),
                        (r, "time_dilute", "time_fed", "time from the drop to the exit (s)")):
    sign, scale = (-1, 1e6) if x == "qm_dilute" else (1, 1)
    ax.scatter(sign * compare[x][both] * scale, sign * compare[y][both] * scale, s=12)
    hi = 1.05 * max((sign * compare[x][both]).max(), (sign * compare[y][both]).max()) * scale
    ax.plot([0, hi], [0, hi], "k--", lw=1, label="fed = dilute")
    ax.set_xlabel(f"{label}, dilute")
    ax.set_ylabel(f"{label}, fed")
    ax.legend(loc="upper left")
fig.suptitle(f"{n} PE spheres of 0.6-1 mm on a level steel feeder {length:g} m long (0.5 mm at "
             f"50 Hz, stroke at 30°), LIGGGHTS:\ndilute against fed at {rate:g} grains/s in "
             f"{lanes} lanes (static model; the grains that left both ways)")
save(fig, "fed_feeder.png")
PYEOF
mkdir -p "$ROOT/docs/dem" && cp fed_feeder.png "$ROOT/docs/dem/"
