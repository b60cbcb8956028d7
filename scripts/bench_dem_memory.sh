#!/usr/bin/env bash
# The charging's peak memory against the grains fed (docs/dem.md, "What it costs"): a
# synthetic contacts.dump of a fed stream as LIGGGHTS writes it (frames every 13 steps of
# 0.76 us, a header each; grains fed at 2000/s, each written 3000 times: 20 impacts, each
# 140 samples of approach, 6 in contact and 4 leaving, as the 10,000-grain run wrote 30
# million samples) for BENCH_MEMORY grains (default "10000 20000"), then the reading of
# its impacts (tribo.dem.contacts.impacts, in a stream) and their charge account
# (tribo.dem.charging.account) in a process of its own, its peak resident memory measured
# by /usr/bin/time -v. Files: out/bench-dem-memory/ (BENCH_OUT; 2.5 GB a 10,000 grains,
# removed after each measurement unless BENCH_KEEP=1).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PY=${PYTHON:-"$ROOT/.venv/bin/python"}
OUT=${BENCH_OUT:-"$ROOT/out/bench-dem-memory"}
mkdir -p "$OUT"
for n in ${BENCH_MEMORY:-10000 20000}; do
  dump="$OUT/contacts-$n.dump"
  "$PY" - "$n" "$dump" <<'PYEOF'
import sys
import numpy as np
n, path = int(sys.argv[1]), sys.argv[2]
RATE, DT, EVERY = 2000.0, 0.76e-6, 13
TAU = DT * EVERY  # s between frames
IMPACTS, APPROACH, TOUCH, LEAVE = 20, 140, 6, 4
BURST = APPROACH + TOUCH + LEAVE
radius = 4e-4
# each burst's first frame: grain g enters at g / RATE, meets the plate every 20 ms
g = np.repeat(np.arange(n), IMPACTS)
k = np.tile(np.arange(IMPACTS), n)
first = np.rint((g / RATE + 0.01 + 0.02 * k) / TAU).astype(np.int64) - APPROACH
frames = int(first.max()) + BURST + 1
header = ("ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n{}\nITEM: BOX BOUNDS ff ff ff\n"
          "-0.005 0.31\n-0.035 0.035\n-0.01 0.04\n"
          "ITEM: ATOMS id x y z vx vy vz radius f_force_walls[3]\n")
CHUNK = 20000  # frames formatted at a time
order = np.argsort(first, kind="stable")
g, first = g[order], first[order]
with open(path, "w") as f:
    for f0 in range(0, frames, CHUNK):
        f1 = min(f0 + CHUNK, frames)
        live = np.flatnonzero((first < f1) & (first + BURST > f0))
        # every (burst, frame) of the chunk
        lo = np.maximum(first[live], f0)
        hi = np.minimum(first[live] + BURST, f1)
        count = hi - lo
        burst = np.repeat(live, count)
        frame = np.repeat(lo, count) + np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
        phase = frame - first[burst]  # 0 .. BURST - 1
        touching = (phase >= APPROACH) & (phase < APPROACH + TOUCH)
        after = phase >= APPROACH + TOUCH
        gap = np.where(touching, -1e-7, np.where(after, 1e-6 * (phase - APPROACH - TOUCH + 1),
                                                 3e-6 * (APPROACH - phase)))
        rows = np.column_stack([
            g[burst] + 1.0, 0.01 + 0.7 * (frame * TAU - g[burst] / RATE),
            -0.03 + 0.0006 * (g[burst] % 100), radius + gap, np.full(len(burst), 0.7),
            np.zeros(len(burst)), np.where(after, 0.2, -0.3), np.full(len(burst), radius),
            np.where(touching, 1e-4, 0.0)])
        at = np.argsort(frame, kind="stable")
        rows, frame = rows[at], frame[at]
        lines = ["%d %.6g %.6g %.6g %.6g %.6g %.6g %.6g %.6g" % tuple(r) for r in rows]
        bounds = np.searchsorted(frame, np.arange(f0, f1 + 1))
        out = []
        for i, fr in enumerate(range(f0, f1)):
            a, b = bounds[i], bounds[i + 1]
            out.append(header.format(fr * EVERY, b - a))
            out.extend(line + "\n" for line in lines[a:b])
        f.write("".join(out))
print(f"{path}: {n} grains, {n * IMPACTS * BURST} samples, {frames} frames")
PYEOF
  ls -l "$dump" | awk '{printf "%.2f GB\n", $5 / 1e9}'
  /usr/bin/time -v -o "$OUT/time-$n.txt" "$PY" - "$n" "$dump" <<'PYEOF'
import sys
import numpy as np
from tribo.dem import contacts
from tribo.dem.charging import GasLimits, account
n, path = int(sys.argv[1]), sys.argv[2]
found = contacts.impacts(path, 0.76e-6, 13, (4.905, 0.0, -8.496), n)
grains = found["grain"].to_numpy()
size = np.full(n, 8e-4)
area = np.full(len(found), 2e-9)
limits = GasLimits(paschen=True)
q, lost = account(grains, -1e-3 * area, area, np.pi * size ** 2, limits.grain(size), -1e-3)
print(f"{n} grains: {len(found)} impacts ({len(found) / n:.3g} a grain), q/m of the first "
      f"{q[0] / (950 * np.pi / 6 * 8e-4 ** 3):.3g} C/kg")
PYEOF
  grep -E "Maximum resident|Elapsed|User time" "$OUT/time-$n.txt"
  [ "${BENCH_KEEP:-0}" = 1 ] || rm -f "$dump"
done
