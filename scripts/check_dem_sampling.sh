#!/usr/bin/env bash
# Does the contacts' sampling of `tribo dem` miss an impact? (docs/dem.md, "Every impact,
# from LIGGGHTS' output"): one LIGGGHTS run writes the contacts as `tribo dem` samples them
# (contacts.dump) and, beside them, the same grains every CHECK_EVERY steps (default 1:
# every step; reference.dump); the impacts read from each are compared impact by impact
# (contacts.compare_impacts: grain, wall, onset time, normal speed), and the reference's
# shortest contact is said against the sampling's interval. Exit 1 where an impact of the
# reference is missed or the sampling finds one it has not (a settling grain's speed
# crossing the threshold below which a grain is not written, for a step or two, is said
# apart: no impact).
#
#   scripts/check_dem_sampling.sh                     # the feeder of bench_dem_sampling.sh
#   scripts/check_dem_sampling.sh -n 4 --seed 2 ...   # any other `tribo dem` options
#
# (--maps: where the impact maps are kept, the results' folder's maps/ by default.)
#
# Results: out/check-dem-sampling/ (CHECK_OUT): the run's folder (dem/, its
# reference_impacts.csv beside impacts.csv) and compared.csv (a row per impact: missed,
# extra, dt and dv_n the found one's less the reference's).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
PY=${PYTHON:-"$ROOT/.venv/bin/python"}
OUT=${CHECK_OUT:-"$ROOT/out/check-dem-sampling"}
EVERY=${CHECK_EVERY:-1}
if [[ $# -eq 0 ]]; then
  set -- -n 40 --seed 1 --epsilon 1 --size uniform:6e-4:1e-3 --stiffness-scale 0.01 \
    --vibration 5e-4,50,30 --tilt-deg 0 --chute-length 0.05
fi
mkdir -p "$OUT"
cd "$OUT"
"$PY" - "$EVERY" --maps "$OUT/maps" "$@" --no-progress --no-plot --out dem --fresh <<'PYEOF'
import json, sys
import pandas as pd
from tribo.cli import dem as cli_dem, main as cli
from tribo.cli.common import run_job
from tribo.dem import contacts

every, argv = int(sys.argv[1]), sys.argv[2:]
args = cli.parser(["dem"]).parse_args(["dem", *argv])


def with_reference(a):
    job = cli_dem.job_of(a)
    job.reference_every = every
    return job


if run_job(args, with_reference, lambda job, report: []) != 0:
    sys.exit(2)
run = json.load(open("dem/liggghts/done.json"))["run"]
dt, sampled = run["dt"], run["sample_every"]
found, reference = pd.read_csv("dem/impacts.csv"), pd.read_csv("dem/reference_impacts.csv")
compared = contacts.compare_impacts(found, reference, sampled * dt)
# a missed one that begins in contact (no sample in flight before it) at about the speed
# below which a grain is not written: a settling grain's speed crossing that threshold
# for a step or two, not an impact
first = reference.merge(compared[compared["missed"] == 1][["grain", "wall", "time"]])
settling = int(((first["from_flight"] == 0)
                & (first["normal_speed"] < 2 * run["slowest"])).sum())
compared.to_csv("compared.csv", index=False)
both = compared[(compared["missed"] == 0) & (compared["extra"] == 0)]
shortest = reference["duration"].min() / dt
missed = int(compared["missed"].sum())
print(f"sampled every {sampled} steps, the reference every {every} (dt {dt:.4g} s): "
      f"{len(found)} impacts found, {len(reference)} in the reference; "
      f"{missed} missed ({settling} of them a settling grain's, beginning in contact below "
      f"{2 * run['slowest']:g} m/s), {int(compared['extra'].sum())} not in the reference")
if len(both):
    print(f"the {len(both)} found in both: onsets at most {both['dt'].abs().max():.3g} s apart, "
          f"normal speeds {both['dv_n'].abs().max():.3g} m/s; "
          f"{int((both['dv_n'].abs() > 1e-6).sum())} more than 1e-6 m/s apart; "
          f"{int(both['sustained_differs'].sum())} read as ending in sustained contact by one "
          f"and not the other")
flown = reference[reference["from_flight"] == 1]
print(f"the reference's shortest contact: {shortest:.0f} steps (to {every}), of an impact from "
      f"flight {flown['duration'].min() / dt:.0f}, against a sample every {sampled}; its "
      f"fastest impact {reference['normal_speed'].max():.4g} m/s")
sys.exit(1 if missed > settling or compared["extra"].any() else 0)
PYEOF
