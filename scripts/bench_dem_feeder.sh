#!/usr/bin/env bash
# A vibratory feeder both ways (issue 44, docs/dem.md "The feeder beside the project's
# population"): the same sphere feed (epsilon 1, PE of 0.6-1 mm on steel, seed 1) through the
# same feeder, a level plate BENCH_LENGTH long (default 0.3 m) moved 0.5 mm at 50 Hz along a
# stroke at 30 degrees to it, as the project's population (the SI FMU's vibrating chute,
# docs/model.md section 9b: `tribo population --vibration`) and in LIGGGHTS (`tribo dem
# --vibration`, dilute: the grains do not meet), each run once here. Prints, for each: the
# conveying speed (the plate's length over the mean exit time), the impacts per grain, the
# stream's mass-weighted q/m and its spread, the impacts a second and the q/m per impact, CPU
# per grain; grain by grain (the same draw: the same feed and seed give the same grains, in
# the same order) the ratio of the q/m, of the impacts and of the exit time; the charged area
# the population's impacts add against a fresh impact's (each grain run again, recorded:
# about 0.5 s of CPU a grain); writes compare.csv (a row per grain), summary.md (the table) and
# feeder.png (the figure) into out/bench-dem-feeder/ (BENCH_OUT).
#
# Needs: the SI FMU with the vibrating chute's parameters (vibration_amplitude,
# vibration_frequency, vibration_angle) and `tribo population --vibration A,F,ANGLE_DEG`;
# LIGGGHTS (scripts/setup.sh). Sizes: BENCH_GRAINS (default 20),
# BENCH_T_END (default 30 s: at about 0.03 m/s a grain crosses 0.3 m in some 10 s),
# BENCH_STIFFNESS (default 0.01: LIGGGHTS' moduli, docs/dem.md). BENCH_REPORT_ONLY=1 makes
# the table and the figure again from the runs already in BENCH_OUT. BENCH_DROP: how the
# population's grains are dropped, `lab` (the default) at rest in the lab, as LIGGGHTS drops
# them (drop_frame=1: the drop's velocity in the lab, the plate's taken off, docs/model.md
# section 9b), or `plate` at rest on the plate (the SI FMU's default: moving with it,
# 0.157 m/s along the stroke at the drop's phase, which the grain keeps for a metre:
# docs/dem.md).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PY=${PYTHON:-"$ROOT/.venv/bin/python"}
OUT=${BENCH_OUT:-"$ROOT/out/bench-dem-feeder"}
N=${BENCH_GRAINS:-20}
LENGTH=${BENCH_LENGTH:-0.3}
T_END=${BENCH_T_END:-30}
STIFF=${BENCH_STIFFNESS:-0.01}
FEED=(--seed 1 --epsilon 1 --size uniform:6e-4:1e-3 --chute-length "$LENGTH" --tilt-deg 0
      --vibration 5e-4,50,30 --t-end "$T_END" --no-progress)
case ${BENCH_DROP:-lab} in
  lab) DROP=(--set drop_frame=1) ;;
  plate) DROP=() ;;
  *) echo "bench_dem_feeder.sh: BENCH_DROP = ${BENCH_DROP}: lab or plate" >&2; exit 2 ;;
esac
mkdir -p "$OUT"
cd "$OUT"
if ! "$PY" -m tribo population --help | grep -q -- "--vibration"; then
  echo "bench_dem_feeder.sh: tribo population has no --vibration (the SI FMU's vibrating chute, docs/model.md section 9b, is needed)" >&2
  exit 2
fi
if [[ ${BENCH_REPORT_ONLY:-0} != 1 ]]; then
  "$PY" -m tribo population -n "$N" "${FEED[@]}" "${DROP[@]}" --serial --no-plot --out population --fresh > /dev/null
  "$PY" -m tribo dem -n "$N" "${FEED[@]}" --stiffness-scale "$STIFF" --maps "$OUT/maps" \
    --no-plot --out dem --fresh | grep "CPU:"
fi

"$PY" - "$N" "$LENGTH" <<'PYEOF'
import json, math, sys
import numpy as np
import pandas as pd
from tribo.plotting import plt, save
n, length = int(sys.argv[1]), float(sys.argv[2])
pop, dem = pd.read_csv("population/particles.csv"), pd.read_csv("dem/particles.csv")
# the same draw: the same grains in the same order (the feed's variables say so)
for c in ("size", "drop_height", "epsilon"):
    assert np.allclose(pop[c], dem[c], rtol=0, atol=0), c
dem_meta = json.load(open("dem/population.json"))
rows = []
for name, d, cpu in (("population (SI FMU, 2D lamina)", pop, pop["cpu_s"].sum() / n),
                     ("LIGGGHTS + charging (3D spheres)", dem,
                      (dem_meta["dem_cpu_s"] + dem_meta["charging_cpu_s"]) / n)):
    left = d[d.exited == 1]
    mass = math.pi / 6 * left["size"] ** 3 * left["density"]
    qm = left["charge_to_mass_static"]
    mean = float((qm * mass).sum() / mass.sum()) if len(left) else math.nan
    spread = float(math.sqrt(((qm - mean) ** 2 * mass).sum() / mass.sum())) if len(left) else math.nan
    rows.append({"model": name, "left": f"{len(left)}/{n}",
                 "conveying speed (m/s)": length / left["exit_time"].mean() if len(left) else math.nan,
                 "impacts per grain": d["impacts"].mean(),
                 "impacts per second": (left["impacts"] / left["exit_time"]).mean(),
                 "q/m per impact (nC/kg)": (left["charge_to_mass_static"] / left["impacts"]).mean() * 1e9,
                 "stream q/m (uC/kg)": mean * 1e6, "spread (uC/kg)": spread * 1e6,
                 "CPU per grain (s)": cpu})
table = pd.DataFrame(rows)
with open("summary.md", "w") as f:
    f.write("| " + " | ".join(table.columns) + " |\n|" + "---|" * len(table.columns) + "\n")
    for row in table.itertuples(index=False):
        f.write("| " + " | ".join(v if isinstance(v, str) else f"{v:.4g}" for v in row) + " |\n")
print(table.to_string(index=False))
both = (pop.exited == 1) & (dem.exited == 1)
compare = pd.DataFrame({"size": pop["size"], "qm_population": pop["charge_to_mass_static"],
                        "qm_dem": dem["charge_to_mass_static"], "impacts_population": pop["impacts"],
                        "impacts_dem": dem["impacts"], "exit_time_population": pop["exit_time"],
                        "exit_time_dem": dem["exit_time"], "both_left": both.astype(int)})
compare.to_csv("compare.csv", index=False)
ratio = (compare.qm_dem / compare.qm_population)[both]
hops = (compare.impacts_dem / compare.impacts_population)[both]
slow = (compare.exit_time_dem / compare.exit_time_population)[both]
print(f"grain by grain ({int(both.sum())} grains that left both ways): q/m DEM / population "
      f"{ratio.mean():.3g} +- {ratio.std():.2g}, impacts {hops.mean():.3g} +- {hops.std():.2g}, "
      f"exit time {slow.mean():.3g} +- {slow.std():.2g}")
fig, (a, b, c) = plt.subplots(1, 3, figsize=(16, 5), layout="constrained")
a.scatter(-compare.qm_population[both] * 1e6, -compare.qm_dem[both] * 1e6, s=14)
lim = [0, 1.05 * max((-compare.qm_population[both]).max(), (-compare.qm_dem[both]).max()) * 1e6]
a.plot(lim, lim, "k--", lw=1, label="equal")
a.set_xlabel("−q/m, the project's population (µC/kg)")
a.set_ylabel("−q/m, LIGGGHTS + charging (µC/kg)")
a.legend(loc="upper left")
b.scatter(compare.impacts_population[both], compare.impacts_dem[both], s=14)
lim = [0, 1.05 * max(compare.impacts_population.max(), compare.impacts_dem.max())]
b.plot(lim, lim, "k--", lw=1, label="equal")
b.set_xlabel("impacts per grain, the project's population")
b.set_ylabel("impacts per grain, LIGGGHTS")
b.legend(loc="upper left")
c.scatter(compare.exit_time_population[both], compare.exit_time_dem[both], s=14)
lim = [0, 1.05 * max(compare.exit_time_population[both].max(), compare.exit_time_dem[both].max())]
c.plot(lim, lim, "k--", lw=1, label="equal")
c.set_xlabel("exit time (s), the project's population")
c.set_ylabel("exit time (s), LIGGGHTS")
c.legend(loc="upper left")
fig.suptitle(f"{n} PE spheres of 0.6-1 mm on a level steel feeder {length:g} m long, 0.5 mm "
             f"at 50 Hz along a stroke at 30° (static model)")
save(fig, "feeder.png")

# Why the lamina's impacts charge less than the map's (docs/dem.md): each population grain
# again, recorded, its impacts found where its count steps; each impact's new charged area
# against the map's for an uncharged grain at its normal and tangential speed (the nearest
# map size, scaled with the size: the cylinder's depth is fixed), in the first and the
# second half of the grain's impacts. And the map's area at one speed and angle with the
# spin the grains land with, against none.
import glob, re
import tribo
from tribo.dem.charging import ANGLES, SPEEDS
maps = {float(re.search(r"-([0-9.]+)m-", f).group(1)): tribo.ImpactMap.load(f)
        for f in glob.glob("maps/*")}
keys = ["size", "phi0_deg", "omega0", "drop_height", "drop_speed", "drop_angle_deg", "epsilon",
        "chute_length", "tilt_deg", "vibration_amplitude", "vibration_frequency",
        "vibration_angle_deg"]
fresh_rows, hits_dem = [], pd.read_csv("dem/impacts.csv")
for _, r in pop.iterrows():
    s = tribo.run_si(r["particle"], r["wall"], t_end=float(r["t_end"]), record_interval=2e-4,
                     outputs=["impacts", "u", "v", "omega", "charged_area"],
                     **{k: float(r[k]) for k in keys})
    hits = s.index[s["impacts"].diff() > 0]
    vn, vt = -s.loc[hits - 1, "v"].to_numpy(), np.abs(s.loc[hits - 1, "u"].to_numpy())
    area = s.loc[hits, "charged_area"].to_numpy() - s.loc[hits - 1, "charged_area"].to_numpy()
    size = min(maps, key=lambda m: abs(math.log(m / r["size"])))
    speed = np.clip(np.hypot(vn, vt), SPEEDS[0], SPEEDS[-1])
    angle = np.clip(np.degrees(np.arctan2(vn, vt)), ANGLES[0], ANGLES[-1])
    new = area / (np.asarray(maps[size]("charged_area", speed, angle, 0.0, 1.0)) * r["size"] / size)
    late = np.arange(len(hits)) >= len(hits) // 2
    fresh_rows.append({"first half": new[~late].mean(), "second half": new[late].mean(),
                       "normal speed": np.median(vn), "angle": np.median(np.degrees(np.arctan2(vn, vt))),
                       "spin": np.median(np.abs(s.loc[hits - 1, "omega"]))})
fresh = pd.DataFrame(fresh_rows)
print("the population's impacts: new charged area over the map's (an uncharged grain's), "
      f"first half {fresh['first half'].mean():.3g} +- {fresh['first half'].std():.2g}, "
      f"second half {fresh['second half'].mean():.3g} +- {fresh['second half'].std():.2g}; "
      f"median normal speed {fresh['normal speed'].mean():.3g} m/s (LIGGGHTS' "
      f"{hits_dem.normal_speed.median():.3g}), angle {fresh['angle'].mean():.3g} deg (LIGGGHTS' "
      f"{hits_dem.angle_deg.median():.3g}), spin {fresh['spin'].mean():.3g} rad/s (the means of the "
      "grains' medians; LIGGGHTS' the median of its impacts)")
# the share of the surface charged at the end: the lamina's bands over its perimeter times
# the cylinder's depth; the sphere's charge over sigma0 times its surface
print("charged at the end: the lamina "
      f"{(pop.charged_area / (math.pi * pop['size'] * pop.cylinder_length)).mean():.3g} of its "
      f"surface, the sphere {(dem.charge_static / (dem.sigma0 * math.pi * dem['size'] ** 2)).mean():.3g}")
spin = float(fresh["spin"].mean())
area = {w: float(tribo.impact_map(speed=[0.2], angle_deg=[70.0], phi0_deg=[0.0], epsilon=[1.0],
                                  omega0=w, settings={"size": 8e-4}, out=f"spin/{w:g}", serial=True,
                                  fresh=True)("charged_area", 0.2, 70.0, 0.0, 1.0))
        for w in (0.0, spin)}
print(f"a fresh impact's area (0.2 m/s at 70 deg, 0.8 mm) with {spin:.3g} rad/s of spin over "
      f"without: {area[spin] / area[0.0]:.6f}")
PYEOF
