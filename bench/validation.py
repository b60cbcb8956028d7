"""The model's values beside the published measurements of docs/validation.md, at the SI
defaults (the gas's limit, docs/model.md section 8e, breakdown_model = paschen; the
materials table's sigma0, 1e-3 C/m2 for the polymer-metal pairs) and, for the changes of
default, at revision 4's (breakdown_model = fixed, breakdown_density 2.7e-5, sigma0
1e-5 C/m2 for PE and nylon on steel): single impacts of PE spheres of 0.2, 2 and 10 mm on
steel against the speed (and the exponent), the angle series, Delta q / A_max beside the
gas's sigma_P of the patch, Ema et al.'s glass bead on aluminium, repeated impacts and their
ceiling, the exit stream of the reference chute, and the separation line's grade and
recovery against the voltage. Writes docs/validation.csv.

    .venv/bin/python bench/validation.py [--out docs/validation.csv] [--grains 1000]
        [--line-grains 300] [--workers 2]
"""

import argparse
import math
import os
import tempfile

import numpy as np
import pandas as pd

import tribo
from tribo import paschen

SPEEDS = (0.5, 1.0, 2.0, 4.0, 8.0)
SIZES = (2e-4, 2e-3, 1e-2)  # the long diameter 2a, m: spheres of 0.2, 2 and 10 mm
# revision 4's defaults (the "before" of every change): the fixed cap, the table's old sigma0
BEFORE_SETTINGS = {"breakdown_model": 0}
BEFORE_TABLE = "[sigma0.steel]\nPE = -1.0e-5\nnylon = 1.0e-5\n"
VOLTAGES = tuple(float(v) for v in range(5000, 40001, 5000))  # across 0.1 m: 50-400 kV/m


def impact_row(case, defaults, particle, wall, speed, size, angle=90.0, materials=None,
               settings=None):
    r = tribo.single_impact(particle, wall, speed=speed, angle_deg=angle, size=size,
                            settings=settings, materials=materials)
    area = r["charged_area"]
    # the gas's limit of the impact's region: the equal-area radius of its largest patch
    conducting = tribo.materials.pair_values(particle, wall)["wall_conducting"]
    limit = paschen.limit(math.sqrt(area / math.pi), conducting=bool(conducting))
    return dict(case=case, defaults=defaults, particle=particle, wall=wall, size_m=size,
                speed_m_s=speed, angle_deg=angle, charge_C=r["charge"], charged_area_m2=area,
                charge_over_area_C_m2=r["charge"] / area, sigma_p_of_patch_C_m2=limit)


def impacts(before: str) -> list[dict]:
    rows = []
    for defaults, materials, settings in (("si", None, None), ("revision 4", before, BEFORE_SETTINGS)):
        for size in SIZES:
            for speed in SPEEDS:
                rows.append(impact_row("head-on speed series", defaults, "PE", "steel", speed,
                                       size, materials=materials, settings=settings))
    for angle in (15, 30, 45, 60, 90):
        rows.append(impact_row("angle series", "si", "PE", "steel", 4.0, 2e-3, angle=angle))
    # Ema et al. 2003: glass beads of 275 um radius on aluminium at 1 m/s
    rows.append(impact_row("Ema et al. 2003 bead", "si", "glass", "aluminium", 1.0, 550e-6))
    return rows


def exponent(rows: list[dict], size: float, defaults: str) -> float:
    s = [r for r in rows if r["case"] == "head-on speed series" and r["size_m"] == size
         and r["defaults"] == defaults]
    v = np.log([r["speed_m_s"] for r in s])
    q = np.log([abs(r["charge_C"]) for r in s])
    return float(np.polyfit(v, q, 1)[0])


def repeated(n: int) -> list[dict]:
    rep = tribo.repeated_impacts("PE", "steel", n, speed=2.0, size=2e-3)
    keep = sorted({1, 2, 10, 100, n} & set(rep["impact"]))
    return [dict(case="repeated impacts", defaults="si", particle="PE", wall="steel",
                 size_m=2e-3, speed_m_s=2.0, angle_deg=90, impacts=int(k),
                 charge_C=float(rep["charge"].iloc[k - 1]), ceiling_C=float(rep["ceiling"].iloc[0]))
            for k in keep]


def streams(grains: int, workers: int, before: str, out: str) -> list[dict]:
    rows = []
    for defaults, materials, settings in (("si", None, {}), ("revision 4", before, BEFORE_SETTINGS)):
        for particle in ("PE", "nylon"):
            pop = tribo.population(grains, seed=1, particle=particle, wall="steel",
                                   settings=dict(settings), materials=materials, workers=workers,
                                   out=os.path.join(out, f"stream-{particle}-{defaults[:2]}"))
            s = pop.summary[(pop.summary["grouping"] == "all") & (pop.summary["model"] == "static")]
            sliding = pop.summary[(pop.summary["grouping"] == "all")
                                  & (pop.summary["model"] == "sliding")]
            res = pop.results
            rows.append(dict(case="reference chute exit stream", defaults=defaults,
                             particle=particle, wall="steel", grains=grains,
                             q_per_m_C_kg=float(s["stream_mean"].iloc[0]),
                             q_per_m_std_C_kg=float(s["stream_std"].iloc[0]),
                             q_per_m_median_C_kg=float(s["p50"].iloc[0]),
                             q_per_m_sliding_C_kg=float(sliding["stream_mean"].iloc[0]),
                             capped_fraction_mean=float(res["capped_fraction_static"].mean()),
                             capped_fraction_sliding_mean=float(
                                 res["capped_fraction_sliding"].mean()),
                             charged_area_mean_m2=float(res["charged_area"].mean())))
    return rows


def line(grains: int, workers: int, before: str, out: str) -> list[dict]:
    rows = []
    for defaults, materials, settings in (("si", None, {}), ("revision 4", before, BEFORE_SETTINGS)):
        mix = tribo.line_sweep(grains, seed=1, voltages=VOLTAGES, settings=dict(settings),
                               materials=materials, workers=workers, figure=False,
                               out=os.path.join(out, f"line-{defaults[:2]}"))
        for r in mix.table.itertuples():
            row = dict(case="separation line", defaults=defaults, particle="PE+nylon",
                       wall="steel", grains=grains, voltage_V=float(r.voltage),
                       field_V_m=float(r.voltage) / 0.1)
            for name in mix.table.columns:
                if name.startswith(("grade_", "recovery_")):
                    row[name] = float(getattr(r, name))
            rows.append(row)
    return rows


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="docs/validation.csv")
    p.add_argument("--grains", type=int, default=1000, help="a chute stream's grains")
    p.add_argument("--line-grains", type=int, default=300, help="the line's grains (0: no line)")
    p.add_argument("--repeated", type=int, default=1000, help="repeated impacts")
    p.add_argument("--workers", type=int, default=2)
    p.add_argument("--work", default=None, help="the runs' folder (default: a temporary one)")
    a = p.parse_args(argv)
    work = a.work or tempfile.mkdtemp(prefix="validation-")
    os.makedirs(work, exist_ok=True)
    before = os.path.join(work, "revision4.toml")
    with open(before, "w") as f:
        f.write(BEFORE_TABLE)
    rows = impacts(before)
    for size in SIZES:
        for defaults in ("si", "revision 4"):
            print(f"PE on steel, {size * 1e3:g} mm, head-on, {defaults}: exponent of |q| in the "
                  f"speed {exponent(rows, size, defaults):.3f}")
    rows += repeated(a.repeated)
    rows += streams(a.grains, a.workers, before, work)
    if a.line_grains:
        rows += line(a.line_grains, a.workers, before, work)
    df = pd.DataFrame(rows)
    df.to_csv(a.out, index=False, float_format="%.6g")
    with pd.option_context("display.width", 250, "display.max_columns", 30):
        print(df.to_string())


if __name__ == "__main__":
    main()
