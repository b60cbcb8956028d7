"""Work-precision report: error against run time, the paper's fixed step against CVODE.

    .venv/bin/python examples/work_precision.py [--build build] [--out docs]

Runs build/tribo_work_precision (the runs and their CPU times, measured in C) and writes
    <out>/work_precision.csv          every run
    <out>/work_precision_chaos.csv    CVODE alone to tau = 3000
    <out>/work_precision.png          error against CPU time, per case and measure
    <out>/work_precision_horizon.png  pointwise error against horizon
    <out>/work_precision.md           the table, with CPU-time ratios at equal error

Error measures (each converges where the motion is regular, which is why it is used):
  * state at tau = 20: max |error| over X, Y, phi, U, V, Omega after a short horizon, the
    direct measure of the integration error before any sensitivity amplifies it;
  * Q_static and Q_sliding at tau = 1000: what users of the model need, converging with
    the integration for regular runs;
  * the energy-balance residual max |E + W_diss - W_ext - E(0)| over the run (model.md §6):
    needs no reference at all.
Errors are against CVODE at rtol = 1e-12 (its own error is estimated from rtol = 1e-11).
For chaotic motion the pointwise error grows with the horizon until it saturates; there
the run's statistics (contact fraction, turns per unit time) are the measures.
"""

import argparse
import io
import math
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

STATE = ["X", "Y", "phi", "U", "V", "Omega"]
CASE_TITLES = {
    "eps0.3_low": "eps = 0.3, mu = nu = 0.1",
    "eps0.9_low": "eps = 0.9, mu = nu = 0.1",
    "eps0.6_high": "eps = 0.6, mu = nu = 1.0",
    "disc_low": "disc eps = 1.0, mu = nu = 0.1",
}
MEASURES = {
    "state_20": "state at tau = 20",
    "Q_static": "Q_static at tau = 1000",
    "Q_sliding": "Q_sliding at tau = 1000",
    "energy_residual": "energy-balance residual",
    "contact_fraction": "contact fraction (statistic)",
}
PAPER_DT = 8e-5


def run_driver(build: Path, mode: str | None) -> pd.DataFrame:
    exe = build / "tribo_work_precision"
    if not exe.exists():
        sys.exit(f"{exe} not found: build the project first (scripts/setup.sh)")
    args = [str(exe)] + ([mode] if mode else [])
    out = subprocess.run(args, check=True, capture_output=True, text=True).stdout
    return pd.read_csv(io.StringIO(out))


def errors(df: pd.DataFrame) -> pd.DataFrame:
    """One row per run with its error in each measure against its case's reference."""
    rows = []
    for case, group in df.groupby("case", sort=False):
        ref = group[group.integrator == "reference"].iloc[0]
        for _, r in group[group.integrator != "reference"].iterrows():
            row = {
                "case": case,
                "integrator": r.integrator,
                "setting": r.setting,
                "cpu_s": r.cpu_s,
                "steps": r.steps,
                "events": r.events,
                "state_20": max(abs(r[f"{q}_20"] - ref[f"{q}_20"]) for q in STATE),
                "Q_static": abs(r.Q_static - ref.Q_static),
                "Q_sliding": abs(r.Q_sliding - ref.Q_sliding),
                "energy_residual": r.energy_residual,
                "contact_fraction": abs(r.contact_fraction - ref.contact_fraction),
            }
            for h in (100, 300, 1000):
                row[f"state_{h}"] = max(abs(r[f"{q}_{h}"] - ref[f"{q}_{h}"]) for q in STATE)
            rows.append(row)
    return pd.DataFrame(rows)


def cpu_at_error(cvode: pd.DataFrame, measure: str, target: float) -> tuple[float, str]:
    """CPU time CVODE needs to reach `target` in `measure`: log-log interpolation between
    the tolerances that bracket it (from loose to tight); the loosest run if it already
    reaches the target (an upper bound on the time needed)."""
    pts = cvode.sort_values("setting", ascending=False)[["setting", "cpu_s", measure]].to_numpy()
    prev = None
    for setting, cpu, err in pts:
        if err <= target:
            if prev is None or prev[2] <= 0 or err <= 0:
                return cpu, f"rtol {setting:.0e}"
            f = (math.log(target) - math.log(prev[2])) / (math.log(err) - math.log(prev[2]))
            cpu_i = math.exp(math.log(prev[1]) + f * (math.log(cpu) - math.log(prev[1])))
            return cpu_i, f"rtol {prev[0]:.0e}..{setting:.0e}"
        prev = (setting, cpu, err)
    return math.nan, "not reached"


def plot_work_precision(err: pd.DataFrame, path: Path) -> None:
    cases = list(CASE_TITLES)
    measures = ["state_20", "Q_static", "Q_sliding", "energy_residual"]
    fig, axes = plt.subplots(len(cases), len(measures), figsize=(16, 14), squeeze=False)
    for i, case in enumerate(cases):
        group = err[err.case == case]
        for j, m in enumerate(measures):
            ax = axes[i][j]
            for integ, style in (("fixed", "o-"), ("cvode", "s-")):
                g = group[group.integrator == integ].sort_values("cpu_s")
                y = g[m].clip(lower=1e-17)
                ax.loglog(g.cpu_s, y, style, label="fixed step (dt)" if integ == "fixed" else "CVODE (rtol)")
                for _, r in g.iterrows():
                    ax.annotate(f"{r.setting:.0e}", (r.cpu_s, max(r[m], 1e-17)), fontsize=6,
                                textcoords="offset points", xytext=(3, 3))
            paper = group[(group.integrator == "fixed") & np.isclose(group.setting, PAPER_DT, rtol=1e-6, atol=0)]
            if len(paper):
                ax.loglog(paper.cpu_s, paper[m].clip(lower=1e-17), "r*", markersize=12,
                          label="paper: dt = 8e-5")
            ax.set_title(f"{CASE_TITLES[case]}\n{MEASURES[m]}", fontsize=9)
            ax.grid(True, which="both", alpha=0.3)
            if i == len(cases) - 1:
                ax.set_xlabel("CPU time per run [s]")
            if j == 0:
                ax.set_ylabel("error")
            if i == 0 and j == 0:
                ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def horizon_errors(chaos: pd.DataFrame) -> pd.DataFrame:
    horizons = sorted({int(c.split("_")[1]) for c in chaos.columns if c.startswith("X_")})
    rows = []
    for case, group in chaos.groupby("case", sort=False):
        ref = group[np.isclose(group.setting, 1e-12, rtol=1e-6, atol=0)].iloc[0]
        for _, r in group[~np.isclose(group.setting, 1e-12, rtol=1e-6, atol=0)].iterrows():
            for h in horizons:
                e = max(abs(r[f"{q}_{h}"] - ref[f"{q}_{h}"]) for q in STATE)
                rows.append({"case": case, "rtol": r.setting, "horizon": h, "error": e})
    return pd.DataFrame(rows)


def plot_horizon(herr: pd.DataFrame, path: Path) -> None:
    cases = list(CASE_TITLES)
    fig, axes = plt.subplots(1, len(cases), figsize=(16, 4), squeeze=False)
    for j, case in enumerate(cases):
        ax = axes[0][j]
        for rtol, g in herr[herr.case == case].groupby("rtol"):
            ax.semilogy(g.horizon, g.error.clip(lower=1e-17), "o-", label=f"rtol {rtol:.0e}")
        ax.set_title(CASE_TITLES[case], fontsize=9)
        ax.set_xlabel("horizon tau")
        if j == 0:
            ax.set_ylabel("max state error vs rtol 1e-12")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def table(err: pd.DataFrame, raw: pd.DataFrame, herr: pd.DataFrame) -> str:
    lines = [
        "| case | measure | fixed dt = 8e-5: error | its CPU [s] | CVODE CPU at that error [s] | "
        "CVODE setting | speed-up at equal error |",
        "|---|---|---|---|---|---|---|",
    ]
    for case in CASE_TITLES:
        group = err[err.case == case]
        paper = group[(group.integrator == "fixed") & np.isclose(group.setting, PAPER_DT, rtol=1e-6, atol=0)].iloc[0]
        cvode = group[group.integrator == "cvode"]
        for m in ["state_20", "Q_static", "Q_sliding", "energy_residual", "contact_fraction"]:
            target = paper[m]
            cpu, where = cpu_at_error(cvode, m, target)
            if cpu == cpu:
                speed_up, cpu_text = f"{paper.cpu_s / cpu:.0f}x", f"{cpu:.3g}"
            else:  # CVODE's tightest run does not reach the fixed step's error here
                speed_up, cpu_text = "-", "-"
            lines.append(
                f"| {CASE_TITLES[case]} | {MEASURES[m]} | {target:.2e} | {paper.cpu_s:.2f} | "
                f"{cpu_text} | {where} | {speed_up} |"
            )
    out = ["\n".join(lines), ""]

    out.append("Reference uncertainty (CVODE rtol 1e-11 against 1e-12, same measures):\n")
    out.append("| case | state at 20 | Q_static | Q_sliding | contact fraction |")
    out.append("|---|---|---|---|---|")
    for case in CASE_TITLES:
        r = err[(err.case == case) & (err.integrator == "reference_check")].iloc[0]
        out.append(f"| {CASE_TITLES[case]} | {r.state_20:.1e} | {r.Q_static:.1e} | "
                   f"{r.Q_sliding:.1e} | {r.contact_fraction:.1e} |")
    out.append("")

    out.append("Pointwise state error against the horizon (CVODE, against rtol 1e-12):\n")
    horizons = sorted(herr.horizon.unique())
    show = [h for h in horizons if h in (250, 1000, 2000, 3000)]
    out.append("| case | rtol | " + " | ".join(f"tau = {h}" for h in show) + " |")
    out.append("|---|---|" + "---|" * len(show))
    for case in CASE_TITLES:
        for rtol, g in herr[herr.case == case].groupby("rtol", sort=False):
            vals = [g[g.horizon == h].error.iloc[0] for h in show]
            out.append(f"| {CASE_TITLES[case]} | {rtol:.0e} | " + " | ".join(f"{v:.1e}" for v in vals) + " |")
    out.append("")

    out.append("Work per run (tau = 1000):\n")
    out.append("| case | integrator | setting | steps | events | CPU [s] |")
    out.append("|---|---|---|---|---|---|")
    for _, r in raw[raw.integrator.isin(["fixed", "cvode"])].iterrows():
        if r.integrator == "fixed" and not np.isclose(r.setting, PAPER_DT, rtol=1e-6, atol=0):
            continue
        if r.integrator == "cvode" and not any(np.isclose(r.setting, s, rtol=1e-6, atol=0) for s in (1e-6, 1e-8, 1e-10)):
            continue
        out.append(f"| {CASE_TITLES[r.case]} | {r.integrator} | {r.setting:.0e} | {r.steps} | "
                   f"{r.events} | {r.cpu_s:.3g} |")
    return "\n".join(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    root = Path(__file__).resolve().parent.parent
    ap.add_argument("--build", type=Path, default=root / "build")
    ap.add_argument("--out", type=Path, default=root / "docs")
    ap.add_argument("--quick", action="store_true", help="smoke test: short horizon, few settings")
    ap.add_argument("--from-csv", action="store_true",
                    help="remake the plots and the table from the CSVs of an earlier run in --out")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    if args.from_csv:
        raw = pd.read_csv(args.out / "work_precision.csv")
    else:
        raw = run_driver(args.build, "quick" if args.quick else None)
        raw.to_csv(args.out / "work_precision.csv", index=False)
    err = errors(raw)
    plot_work_precision(err, args.out / "work_precision.png")
    if args.quick:
        print(err.to_string())
        return
    if args.from_csv:
        chaos = pd.read_csv(args.out / "work_precision_chaos.csv")
    else:
        chaos = run_driver(args.build, "chaos")
        chaos.to_csv(args.out / "work_precision_chaos.csv", index=False)
    herr = horizon_errors(chaos)
    plot_horizon(herr, args.out / "work_precision_horizon.png")
    md = table(err, raw, herr)
    (args.out / "work_precision.md").write_text(
        "# Work-precision: the paper's fixed step against CVODE\n\n"
        "Produced by `scripts/work_precision.sh` (examples/work_precision.py); every number below "
        "was measured in that run. CPU times are per run of tau = 1000 on this machine; ratios "
        "are measured in one run. Every run has the default normal dashpot, on the contact point "
        "(docs/model.md section 3).\n\n"
        "![work-precision](work_precision.png)\n\n![horizon](work_precision_horizon.png)\n\n" + md + "\n"
    )
    print(md)


if __name__ == "__main__":
    main()
