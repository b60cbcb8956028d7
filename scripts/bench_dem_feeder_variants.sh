#!/usr/bin/env bash
# The feeder's speed gap, each suspect tried alone (issue 44, docs/dem.md "The feeder beside
# the project's population"): the level feeder of bench_dem_feeder.sh (0.5 mm at 50 Hz along
# a stroke at 30 degrees, PE spheres of 0.6-1 mm on steel, epsilon 1, seed 1, dilute), the
# same BENCH_GRAINS grains (default 10) each way, over BENCH_LENGTH (default 0.3 m):
#
#   LIGGGHTS (`tribo dem --stiffness-scale 0.01`): its default law (Hertz-Mindlin with the
#     tangential history, the constant-torque rolling friction cdt), then one change each:
#     no tangential history (no Mindlin spring), rolling friction off, the rolling friction
#     epsd2 (an elastic-plastic spring, which holds a grain from turning as the model's
#     rolling lock does), the linear `hooke` law (its stiffness Hertz's at 0.2 m/s, the
#     impacts' normal speed; the same restitution);
#   the population (`tribo population`, the SI FMU): its default, the compliant stick
#     (stick_model 0: the tangential spring in every contact), no rolling resistance
#     (mu_roll 0), and the grains dropped at rest in the lab as LIGGGHTS drops them
#     (drop_frame=1: by default the population's drop velocity is the grain's relative to
#     the plate, docs/model.md section 9b, which moves along the stroke at 2 pi f A =
#     0.157 m/s at the drop's phase), with and without rolling resistance, and with only the
#     plate's velocity along the plate cancelled (a drop speed against it);
#   both again over BENCH_LONG (default 1 m), the default drops and the population's at
#     rest in the lab: the speed between BENCH_LENGTH and BENCH_LONG, the same grains, is
#     the feeder's own, its drop forgotten.
#
# Prints a table (and writes it to summary.md) of each run's conveying speed (the length over
# the mean exit time), impacts per grain, impacts a second, the advance per impact, and the
# grains' rolling invariant at the exit, L/(m r) = u + (I/(m r^2)) r omega_forward in the lab
# (the angular momentum about the contact point, which no force at the contact changes:
# only the rolling resistance's torque); then, for one grain of 0.8 mm in the population,
# L/(m a) at its impacts, dropped both ways, with and without rolling resistance.
# And whether LIGGGHTS' spheres move in their lane's plane (y and vy of every sample of the
# default run's contacts, 0 where they do). About 10 min of LIGGGHTS' CPU at the defaults (6
# of them the 1 m run); a run already in BENCH_OUT (default out/bench-dem-feeder-variants)
# with the same settings is kept (BENCH_FRESH=1: all again). BENCH_SPIN=1 runs LIGGGHTS'
# rolling-off input again with the grains' velocity and spin dumped every 500 steps and
# prints their L/(m r) in flight along the plate and at the last sample (2 min more). BENCH_T_END (default 60 s) the horizon: another cuts
# LIGGGHTS' run into other pieces and the population's into other output steps, which moves
# a chaotic hop's numbers by a few per cent (docs/dem.md).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PY=${PYTHON:-"$ROOT/.venv/bin/python"}
OUT=${BENCH_OUT:-"$ROOT/out/bench-dem-feeder-variants"}
N=${BENCH_GRAINS:-10}
LENGTH=${BENCH_LENGTH:-0.3}
LONG=${BENCH_LONG:-1.0}
STIFF=${BENCH_STIFFNESS:-0.01}
T_END=${BENCH_T_END:-60}
AMPLITUDE=5e-4 FREQUENCY=50 ANGLE=30
FEED=(--seed 1 --epsilon 1 --size uniform:6e-4:1e-3 --tilt-deg 0
      --vibration "$AMPLITUDE,$FREQUENCY,$ANGLE" --no-progress)
FRESH=()
[[ ${BENCH_FRESH:-0} == 1 ]] && FRESH=(--fresh)
# the population's grain dropped at rest in the lab (model.md section 9b)
LAB=(--set drop_frame=1)
# only the plate's velocity along the plate cancelled, at phase 0
ALONG=(--drop-speed "$("$PY" -c "import math; print(2 * math.pi * $FREQUENCY * $AMPLITUDE * math.cos(math.radians($ANGLE)))")"
       --drop-angle-deg -90)
mkdir -p "$OUT"
cd "$OUT"

pop() {  # NAME LENGTH [options]: the population, serially
  local name=$1 length=$2; shift 2
  "$PY" -m tribo population -n "$N" "${FEED[@]}" --chute-length "$length" --t-end "$T_END" "$@" \
    --serial --no-plot --out "pop-$name" --fresh > /dev/null
}
dem() {  # NAME LENGTH [options]: LIGGGHTS, one run at a time, one rank
  local name=$1 length=$2; shift 2
  echo "dem-$name: $("$PY" -m tribo dem -n "$N" "${FEED[@]}" --chute-length "$length" --t-end "$T_END" \
    --stiffness-scale "$STIFF" --maps "$OUT/maps" --no-plot --out "dem-$name" "${FRESH[@]}" "$@" \
    | grep "CPU:")"
}

pop default "$LENGTH"
pop compliant-stick "$LENGTH" --set stick_model=0
pop no-rolling "$LENGTH" --set mu_roll=0
pop lab "$LENGTH" "${LAB[@]}"
pop lab-no-rolling "$LENGTH" "${LAB[@]}" --set mu_roll=0
pop lab-along "$LENGTH" "${ALONG[@]}"
pop default-long "$LONG"
pop lab-long "$LONG" "${LAB[@]}"
dem default "$LENGTH"
dem no-history "$LENGTH" --contact-law "hertz tangential no_history rolling_friction cdt"
dem rolling-off "$LENGTH" --contact-law "hertz tangential history rolling_friction off"
dem epsd2 "$LENGTH" --contact-law "hertz tangential history rolling_friction epsd2"
dem hooke "$LENGTH" --contact-law "hooke tangential history rolling_friction cdt" \
  --contact-property "characteristicVelocity scalar 0.2"
dem default-long "$LONG"

if [[ ${BENCH_SPIN:-0} == 1 ]]; then  # the same input, one dump more, by hand
  rm -rf spin && mkdir spin && cp dem-rolling-off/liggghts/{in.liggghts,plate.stl,sides.stl} spin/
  sed -i '/^dump_modify contacts flush no$/a dump spin all custom 500 spin.dump id x z vx vz omegay radius\ndump_modify spin flush no' spin/in.liggghts
  (cd spin && liggghts -in in.liggghts -log log.liggghts -echo none > /dev/null)
  "$PY" - "$LENGTH" <<'PYEOF'
import sys
import numpy as np
import pandas as pd
length = float(sys.argv[1])
d = pd.read_csv("spin/spin.dump", sep=r"\s+", header=None, comment="I", on_bad_lines="skip",
                names=["id", "x", "z", "vx", "vz", "wy", "r"])
d = d[d["r"].notna()]
marks = np.linspace(0, length, 7)[1:-1].tolist() + [0.97 * length]
print("LIGGGHTS without rolling friction: L/(m r) = vx + 2/5 r omega_y (m/s) in flight near x = "
      + ", ".join(f"{x:.3g}" for x in marks) + " m, and at the grain's last sample:")
for grain, s in d.groupby("id"):
    L, x = (s["vx"] + 0.4 * s["r"] * s["wy"]).to_numpy(), s["x"].to_numpy()
    flight = (s["z"] - s["r"] > 3e-4).to_numpy()  # above the plate's highest, 0.25 mm
    near = [np.median(L[max(i - 20, 0):i + 20][flight[max(i - 20, 0):i + 20]])
            for i in np.searchsorted(x, marks)]
    print(f"  grain {int(grain)}: " + " ".join(f"{v:+.4f}" for v in near)
          + f"; last {L[-1]:+.4f} at x = {x[-1]:.4f} m")
PYEOF
fi

"$PY" - "$LENGTH" "$LONG" "$AMPLITUDE" "$FREQUENCY" "$ANGLE" <<'PYEOF'
import math, sys
import numpy as np
import pandas as pd
import tribo
length, long, A, f, psi = (float(x) for x in sys.argv[1:])
w = 2 * math.pi * f
plate_u = lambda t: A * w * math.cos(math.radians(psi)) * np.cos(w * np.asarray(t))

def invariant(d, engine):
    """L/(m r) at the exit, lab frame: the DEM's u is the lab's, its omega the population's
    sign (negative rolling forward); the population's u is relative to the plate."""
    r = d["size"] / 2
    if engine == "dem":
        return d["u"] - 0.4 * r * d["omega"]
    return d["u"] + plate_u(d["exit_time"]) - 0.5 * r * d["omega"]

runs = [("LIGGGHTS", "dem", "default", "Hertz-Mindlin, tangential history, rolling cdt (mu_r 0.01)"),
        ("LIGGGHTS", "dem", "no-history", "tangential no_history"),
        ("LIGGGHTS", "dem", "rolling-off", "rolling_friction off"),
        ("LIGGGHTS", "dem", "epsd2", "rolling_friction epsd2"),
        ("LIGGGHTS", "dem", "hooke", "model hooke (linear, stiffness Hertz's at 0.2 m/s)"),
        ("population", "pop", "default", "default: dropped at rest relative to the plate"),
        ("population", "pop", "compliant-stick", "stick_model 0 (compliant)"),
        ("population", "pop", "no-rolling", "mu_roll 0"),
        ("population", "pop", "lab", "dropped at rest in the lab, as LIGGGHTS"),
        ("population", "pop", "lab-no-rolling", "at rest in the lab, mu_roll 0"),
        ("population", "pop", "lab-along", "only the plate's velocity along the plate cancelled")]
rows = []
for who, engine, name, what in runs:
    d = pd.read_csv(f"{engine}-{name}/particles.csv")
    left = d[d.exited == 1]
    rows.append({"engine": who, "variant": what, "left": f"{len(left)}/{len(d)}",
                 "conveying speed (m/s)": length / left["exit_time"].mean(),
                 "impacts per grain": d["impacts"].mean(),
                 "impacts per second": (left["impacts"] / left["exit_time"]).mean(),
                 "advance per impact (mm)": 1e3 * length / left["impacts"].mean(),
                 "L/(m r) at the exit (m/s)": invariant(left, engine).mean()})
table = pd.DataFrame(rows)
with open("summary.md", "w") as out:
    out.write("| " + " | ".join(table.columns) + " |\n|" + "---|" * len(table.columns) + "\n")
    for row in table.itertuples(index=False):
        out.write("| " + " | ".join(v if isinstance(v, str) else f"{v:.4g}" for v in row) + " |\n")
print(table.to_string(index=False))
print(f"over {length:g} to {long:g} m, the same grains (the speed between, and the mean over "
      f"{long:g} m):")
for who, engine, name in (("LIGGGHTS", "dem", "default"), ("population", "pop", "default"),
                          ("population at rest in the lab", "pop", "lab")):
    short = pd.read_csv(f"{engine}-{name}/particles.csv")
    far = pd.read_csv(f"{engine}-{name}-long/particles.csv")
    assert (short.exited == 1).all() and (far.exited == 1).all(), name
    print(f"  {who}: {(long - length) / (far.exit_time - short.exit_time).mean():.4f} m/s between, "
          f"{long / far.exit_time.mean():.4f} over {long:g} m, {far.impacts.mean():.1f} impacts")

# the sphere's plane: its lane's y and no velocity across it, in every sample of the contacts
dump = pd.read_csv("dem-default/liggghts/contacts.dump", sep=r"\s+", header=None,
                   names=["id", "x", "y", "z", "vx", "vy", "vz", "r", "fy", "fz"],
                   comment="I", on_bad_lines="skip")
dump = dump[dump["r"].notna()]
across = dump.groupby("id")["y"].agg(lambda y: y.max() - y.min()).max()
print(f"LIGGGHTS' default run: {len(dump)} samples of {dump['id'].nunique()} grains, the most a "
      f"grain's y moves {across:.3g} m, the largest |vy| {dump['vy'].abs().max():.3g} m/s")

# the invariant at a population grain's impacts: kept exactly without rolling resistance,
# drawn by it towards the feeder's own, from either drop
print(f"L/(m a) (m/s) of a 0.8 mm grain at its impacts 1, 2, 6, 21, 41 and the last before "
      f"{length:g} m or 3 s:")
for mu_roll in (0.0, 0.01):
    for label, frame in (("at rest on the plate", 0), ("at rest in the lab", 1)):
        s = tribo.run_si("PE", "steel", t_end=3.0, record_interval=1e-4,
                         outputs=["impacts", "u", "omega"], size=8e-4, epsilon=1.0,
                         chute_length=length, tilt_deg=0, vibration_amplitude=A,
                         vibration_frequency=f, vibration_angle_deg=psi, mu_roll=mu_roll,
                         drop_frame=frame)
        L = s["u"] + plate_u(s["time"]) - 0.5 * 4e-4 * s["omega"]
        hits = s.index[s["impacts"].diff() > 0]
        at = L[hits - 1].to_numpy()
        print(f"  mu_roll {mu_roll:g}, dropped {label}: "
              + " ".join(f"{at[i]:.4f}" for i in (0, 1, 5, 20, 40, -1) if -len(at) <= i < len(at))
              + f" ({len(at)} impacts)")
PYEOF
