"""The reference case (docs/reference_case.md) through the SI FMU (tribo.run_si): its
figure, and a sweep over the particle's size and shape with q/m at the chute's exit.
Writes docs/reference_case/: trajectory.png, sweep.png, sweep.csv.

    .venv/bin/python examples/reference_case.py [--out docs/reference_case]

The reference case: a 1 mm polyethylene grain (a = 0.5 mm, epsilon 0.6) dropped 10 mm
straight down onto a 0.3 m steel chute tilted 30 degrees, mu = nu = 0.3, both charge
models (the SI FMU's defaults with chute_length = 0.3). The sweep varies the size
2a (0.1 .. 5 mm) and epsilon, each over four initial orientations phi0 (the bouncing is
chaotic: one run is one sample), and plots the mean and range of q/m at the exit; every
run goes to the exit, and its CPU time is in the CSV.
"""

import argparse
import os
import time

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import tribo  # noqa: E402

CHUTE = dict(chute_length=0.3)
SIZES_MM = [0.1, 0.2, 0.5, 1.0, 2.0, 5.0]
EPSILONS = [0.3, 0.6, 1.0]
PHI0_DEG = [0.0, 45.0, 90.0, 135.0]


def trajectory(out):
    df = tribo.run_si("PE", "steel", size=1e-3, record_interval=1e-4, **CHUTE)
    t_ms = 1e3 * df["time"]
    exit_ms = 1e3 * df["exit_time"].iloc[-1]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    ax1.plot(t_ms, 1e3 * df["y"], lw=0.8, label="centre's height y")
    ax1.set_ylabel("height above the chute [mm]")
    ax2.plot(t_ms, 1e6 * df["charge_to_mass_sliding"], label="sliding model")
    ax2.plot(t_ms, 1e6 * df["charge_to_mass_static"], label="static model")
    ax2.set_ylabel("q/m [µC/kg]")
    ax2.set_xlabel("time [ms]")
    for ax in (ax1, ax2):
        ax.axvline(exit_ms, color="k", ls="--", lw=0.8, label=f"exit at {exit_ms:.0f} ms")
        ax.legend(loc="best", fontsize=8)
        ax.grid(alpha=0.3)
    ax1.set_title("1 mm PE grain (ε 0.6) dropped 10 mm onto a 0.3 m steel chute at 30°")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "trajectory.png"), dpi=120)
    plt.close(fig)
    last = df.iloc[-1]
    print(f"exit {last['exit_time']:.4g} s, u {last['u']:.4g} m/s, q/m static "
          f"{1e6 * last['charge_to_mass_static']:.4g} uC/kg, sliding "
          f"{1e6 * last['charge_to_mass_sliding']:.4g} uC/kg, impacts {last['impacts']:.0f}")


def sweep(out):
    rows = []
    names = ["exit_time", "u", "impacts", "contact_fraction", "charge_to_mass_static",
             "charge_to_mass_sliding"]
    for size in SIZES_MM:
        for eps in EPSILONS:
            for phi0_deg in PHI0_DEG:
                cpu = time.process_time()
                # 2 * (size * 0.5e-3): the FMU's semi-major axis exactly as before (halving
                # and doubling are exact)
                df = tribo.run_si("PE", "steel", size=2 * (size * 0.5e-3), epsilon=eps,
                                  phi0_deg=phi0_deg, t_end=2.0, record_interval=0.01,
                                  outputs=names, **CHUTE)
                cpu = time.process_time() - cpu
                last = df.iloc[-1]
                rows.append(dict(size_mm=size, epsilon=eps, phi0_deg=phi0_deg, cpu_s=cpu,
                                 **{n: float(last[n]) for n in names}))
                print(f"2a {size} mm, epsilon {eps}, phi0 {phi0_deg:g} deg: exit {last['exit_time']:.4g} s, "
                      f"{last['impacts']:.0f} impacts, CPU {cpu:.3g} s", flush=True)
    res = pd.DataFrame(rows)
    res.to_csv(os.path.join(out, "sweep.csv"), index=False)
    print(f"{len(res)} runs, CPU per run {res.cpu_s.min():.3g} .. {res.cpu_s.max():.3g} s "
          f"(median {res.cpu_s.median():.3g} s, total {res.cpu_s.sum():.3g} s; the "
          f"orientations 0 and 45 degrees alone: {res[res.phi0_deg < 50].cpu_s.sum():.3g} s)")
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    for ax, model, label in ((axes[0], "charge_to_mass_static", "static model"),
                             (axes[1], "charge_to_mass_sliding", "sliding model")):
        for eps in EPSILONS:
            g = res[res.epsilon == eps].groupby("size_mm")[model]
            mean, lo, hi = (-1e6 * g.mean(), -1e6 * g.max(), -1e6 * g.min())
            line, = ax.plot(mean.index, mean, "o-", label=f"ε = {eps}")
            ax.fill_between(mean.index, lo, hi, color=line.get_color(), alpha=0.2)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("particle size 2a [mm]")
        ax.set_ylabel("−q/m at the exit [µC/kg]")
        ax.set_title(f"{label}: mean and range over {len(PHI0_DEG)} orientations φ0", fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.suptitle("PE on steel, 30°, 0.3 m chute, 10 mm drop (q/m < 0: plotted −q/m); "
                 f"all {len(res)} runs to the exit", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "sweep.png"), dpi=120)
    plt.close(fig)
    print(res.groupby(["size_mm", "epsilon"])[["charge_to_mass_static", "charge_to_mass_sliding",
                                                "impacts"]].mean().to_string())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="docs/reference_case")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    trajectory(args.out)
    sweep(args.out)


if __name__ == "__main__":
    main()
