#!/usr/bin/env bash
# Whether the event-driven integrators lose a switch at a contact's start on a still plate
# (docs/integrators.md, "A switch that starts at 0"): N random SI drops without spin (discs and
# ellipses, level and tilted plates up to 34 degrees, oblique drops, mu_roll 0, 0.01 or
# 0.001..0.1, mu 0.3 or 0.05..1), each run through its first contact by CVODE Adams, CVODE BDF,
# DOP853 (on a still plate by a stroke of 1e-25 m) and, with the compliant stick, the fixed step
# (dt 3e-4, v_reg 1e-9); the largest of |X, Y, phi, U, V, Omega| apart from DOP853 (and the
# fixed step) at tau_c + 0.5, 1 and 3, and how many set-ups lie over 1e-6 apart. With --before
# REV the same first for revision REV's core (bench/first_contacts.c compiled against it).
# Usage: scripts/bench_first_contacts.sh [--before REV] [N=4000] [SEED=7] [STICK_MODEL=0|1]
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# shellcheck source=bench_before.sh
. "$ROOT/scripts/bench_before.sh"
n=${1:-4000}
seed=${2:-7}
stick=${3:-0}
[ -x "$ROOT/build/tribo_first_contacts" ] || "$ROOT/scripts/setup.sh" >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
runs=("this tree|$ROOT/build/tribo_first_contacts")
if [ -n "$before" ]; then
  before_program "$ROOT/bench/first_contacts.c" "$tmp/before"
  runs=("before ($before)|$tmp/before" "${runs[@]}")
fi
"$ROOT/.venv/bin/python" - "$n" "$seed" "$stick" > "$tmp/setups.txt" <<'PY'
import math
import sys

import numpy as np

n, seed, stick = int(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
rng = np.random.default_rng(seed)
for _ in range(n):
    eps = 1.0 if rng.random() < 0.5 else rng.uniform(0.3, 1.0)
    tilt = 0.0 if rng.random() < 0.4 else rng.uniform(0, 0.6)
    drop_angle = 0.0 if rng.random() < 0.4 else rng.uniform(-0.4, 0.4)
    height = rng.uniform(1e-3, 2e-2)
    r = rng.random()
    mu_roll = 0.0 if r < 0.25 else 0.01 if r < 0.6 else 10 ** rng.uniform(-3, -1)
    mu = 0.3 if rng.random() < 0.5 else rng.uniform(0.05, 1.0)
    a = rng.uniform(2e-4, 1e-3)
    phi0 = rng.uniform(0, math.pi)
    # dropped from just above the plate at the speed of a fall from `height`
    print(f"epsilon={eps} semi_major_axis={a} phi0={phi0} tilt={tilt} drop_angle={drop_angle} "
          f"drop_height=1e-6 drop_speed={math.sqrt(2 * 9.81 * height)} mu_roll={mu_roll} mu={mu} "
          f"chute_length=1 stick_model={stick}")
PY
integrators=("integrator=1" "integrator=2" "integrator=1 vibration_amplitude=1e-25 vibration_frequency=50")
[ "$stick" = 0 ] && integrators+=("integrator=0 dt=3e-4 v_reg=1e-9")
for run in "${runs[@]}"; do
  echo "${run%%|*}:"
  "${run#*|}" "$tmp/setups.txt" "" "${integrators[@]}" > "$tmp/out.txt"
  "$ROOT/.venv/bin/python" - "$tmp/out.txt" <<'PY'
import sys

import numpy as np

# columns: grain, integrator, tau - tau_c, status, X, Y, phi, U, V, Omega, in_contact, impacts
a = np.loadtxt(sys.argv[1], ndmin=2)
names = ["CVODE Adams", "CVODE BDF", "DOP853", "fixed step"]
present = sorted(set(a[:, 1].astype(int)))
# the CVODE runs against DOP853, and all three against the fixed step where it ran
for ref in [r for r in (2, 3) if r in present]:
    for k in range(ref):
        for after in sorted(set(a[:, 2])):
            # grain by grain, where both runs reached that time
            r = {int(row[0]): row for row in a[(a[:, 1] == ref) & (a[:, 2] == after)]}
            x = {int(row[0]): row for row in a[(a[:, 1] == k) & (a[:, 2] == after)]}
            d = np.array([np.max(np.abs(x[g][4:10] - r[g][4:10])) for g in r if g in x])
            print(f"{names[k]} against {names[ref]} at tau_c + {after:g}: median {np.median(d):.2g}, "
                  f"largest {d.max():.2g}, {(d > 1e-6).sum()} of {len(d)} over 1e-6")
PY
done
