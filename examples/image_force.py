"""A co-simulation master that closes the image-charge loop through the SI FMU's inputs:
every communication step it reads the particle's charge per unit length and its height,
and feeds the pull of the charge's image in the grounded chute back as F_N_ext.

    .venv/bin/python examples/image_force.py [--out docs/image_force] [--charge sliding]

The approximation (docs/image_force.md):
- the particle's charge is a line charge lambda (C/m, the FMU's charge_per_length_<model>)
  on the cylinder's axis, at the centre's height y above the chute;
- the chute is a grounded conductor filling the half space below its surface, so the
  charge's image is -lambda at depth y, and the pull per unit length is
      F_N_ext = -lambda^2 / (4 pi eps0 y)      (towards the chute: negative);
- that holds for y much larger than the distance from the charge to the surface; near
  contact the charge sits on the surface, not on the axis, and the line-charge force is only
  an order of magnitude. The height is bounded below by the semi-minor axis b = epsilon a,
  the lowest the centre of an undeformed particle can be (an indentation takes it below b
  by at most a few Gamma a), so the force stays finite;
- the charge fed back is capped at the air-breakdown density all round,
  |lambda| <= 2.7e-5 C/m^2 x the perimeter: a surface holds no more, and the provisional
  sliding model's density has no such bound (with the loop closed, pull -> normal force ->
  frictional work -> charge -> pull runs away without it);
- the force is held over each communication step (the FMU's inputs are piecewise
  constant), so the step must be short against the time the height changes in.

It writes, under --out: threshold.csv / threshold.png (the sizes at which the image force
at contact exceeds the weight per length m' g cos(tilt), at the air-breakdown density and at
the reference case's q/m) and coupled.png (the reference case with the loop closed and
open), and prints the cost of a coupled step against the uncoupled run (CPU seconds of the
instance's steps; the fastest of 3 runs, where a run is short).
"""

import argparse
import math
import os
import time

import numpy as np

import tribo
from tribo.fmu import FmuImage, Instance, unpacked

EPS0 = 8.8541878128e-12  # F/m
BREAKDOWN_SIGMA = 2.7e-5  # C/m^2, the air-breakdown limit on a surface charge density


def image_force_per_length(charge_per_length, y, b):
    """The pull of a line charge's image in a grounded conducting plane, per unit length
    (N/m, negative: towards the plane), at the height y bounded below by b."""
    return -charge_per_length ** 2 / (4.0 * math.pi * EPS0 * max(y, b))


def run_coupled(params, t_end, step, charge="sliding", couple=True, outputs=("y",)):
    """One run of the SI FMU from 0 to t_end in communication steps of `step` s, the image
    force fed back every step (couple=False: never set). Returns (times, rows of `outputs`
    plus "lambda" (the charge per length fed back, capped) and "F_N_ext" as the FMU holds it
    over each step; the last row has the outputs at the end), the instance's CPU seconds,
    whether the FMU ended the run at the chute's exit)."""
    image = FmuImage.load(tribo.find_fmu(3, variant="si"))
    names = list(dict.fromkeys(["y", f"charge_per_length_{charge}", *outputs]))
    times, rows = [0.0], []
    with unpacked(image) as fmu_dir, Instance(fmu_dir, name="image_force") as inst:
        inst.set_parameters(params)
        inst.init(0.0, t_end)
        b = inst.get("epsilon") * inst.get("semi_major_axis")
        cpu = time.process_time()
        n = int(round(t_end / step))
        values = inst.get_many(names)
        # the most charge the surface holds: the breakdown density all round
        cap = BREAKDOWN_SIGMA * ellipse_perimeter(inst.get("semi_major_axis"), b)
        for k in range(1, n + 1):
            lam = math.copysign(min(abs(values[f"charge_per_length_{charge}"]), cap),
                                values[f"charge_per_length_{charge}"])
            force = image_force_per_length(lam, values["y"], b) if couple else 0.0
            if couple:
                inst.set(F_N_ext=force)
            # the force as the FMU holds it over the step
            rows.append(dict(values, **{"lambda": lam, "F_N_ext": inst.get("F_N_ext")}))
            going = inst.step_to(min(k * step, t_end))
            times.append(inst.t)
            values = inst.get_many(names)
            if not going:
                break
        rows.append(dict(values, **{"lambda": float("nan"), "F_N_ext": float("nan")}))
        cpu = time.process_time() - cpu
        return np.array(times), rows, cpu, inst.ended


def ellipse_perimeter(a, b):
    """The ellipse's perimeter by Ramanujan's second approximation (relative error 2e-11 at
    b/a = 0.6, 7e-8 at 0.3, 1e-5 at 0.1: against a 2e6-sided polygon)."""
    h = ((a - b) / (a + b)) ** 2
    return math.pi * (a + b) * (1.0 + 3.0 * h / (10.0 + math.sqrt(4.0 - 3.0 * h)))


def threshold_table(sizes_mm, epsilon, density, tilt, q_per_m, g=9.81):
    """Image force at contact (y = b) over the weight per length, per size: for a charge
    density at the breakdown limit over the whole surface, and for a given q/m."""
    rows = []
    for size in sizes_mm:
        a = 0.5e-3 * size
        b = epsilon * a
        weight = density * math.pi * a * b * g * math.cos(tilt)  # m' g cos(tilt), N/m
        lam_breakdown = BREAKDOWN_SIGMA * ellipse_perimeter(a, b)
        lam_qm = q_per_m * density * math.pi * a * b
        rows.append(dict(size_mm=size, weight_N_per_m=weight,
                         ratio_breakdown=-image_force_per_length(lam_breakdown, b, b) / weight,
                         ratio_reference_qm=-image_force_per_length(lam_qm, b, b) / weight))
    return rows


def main():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="docs/image_force")
    parser.add_argument("--charge", choices=("static", "sliding"), default="sliding")
    parser.add_argument("--t-end", type=float, default=0.5)
    parser.add_argument("--step", type=float, default=1e-4)
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    # the reference case (docs/reference_case.md) on its 0.3 m chute
    params = tribo.materials.start_values("PE", "steel", chute_length=0.3)
    si_defaults = {v.name: float(v.start) for v in
                   FmuImage.load(tribo.find_fmu(3, variant="si")).model_description().modelVariables
                   if v.causality == "parameter" and v.start is not None
                   and v.name in ("semi_major_axis", "epsilon", "tilt")}
    density = params["density"]

    # 1. when the image force matters
    plain_t, plain, plain_cpu, _ = run_coupled(params, args.t_end, args.step, args.charge,
                                               couple=False, outputs=("y", "charge_to_mass_" + args.charge))
    # CPU times: the fastest of 3 runs (the machine may be shared)
    plain_cpu = min([plain_cpu] + [run_coupled(params, args.t_end, args.step, args.charge, couple=False)[2]
                                   for _ in range(2)])
    q_per_m = abs(plain[-1]["charge_to_mass_" + args.charge])
    sizes = [0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0]
    table = pd.DataFrame(threshold_table(sizes, si_defaults["epsilon"], density,
                                         si_defaults["tilt"], q_per_m))
    table.to_csv(os.path.join(args.out, "threshold.csv"), index=False)
    print(f"image force at contact / weight per length (epsilon {si_defaults['epsilon']}, "
          f"PE, tilt {math.degrees(si_defaults['tilt']):.0f} deg); q/m = {q_per_m * 1e6:.3g} uC/kg is "
          f"the {args.charge} model's at t = {plain_t[-1]:.3g} s of the reference case")
    print(table.to_string(index=False, float_format=lambda v: f"{v:.3g}"))
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    ax.loglog(table.size_mm, table.ratio_breakdown, "o-",
              label=f"σ = {BREAKDOWN_SIGMA:g} C/m² (air breakdown) all round")
    ax.loglog(table.size_mm, table.ratio_reference_qm, "s-",
              label=f"q/m = {q_per_m * 1e6:.3g} µC/kg ({args.charge} model, reference case)")
    ax.axhline(1.0, color="k", lw=0.8, ls="--", label="image force = weight")
    ax.set_xlabel("particle size 2a [mm]")
    ax.set_ylabel("image force at contact / m′ g cos β")
    ax.set_title(f"PE particle (ε {si_defaults['epsilon']}) on a grounded chute at "
                 f"{math.degrees(si_defaults['tilt']):.0f}°: line-charge image at y = b", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "threshold.png"), dpi=120)
    plt.close(fig)

    # 2. the reference case with the loop closed, and its cost: with the static model's
    # charge (a pull 1e-7 of the weight: the same path, but a new input every step) the
    # difference is the loop's own cost; with the chosen model's, the path changes too
    for charge in dict.fromkeys(("static", args.charge)):
        coupled_t, coupled, coupled_cpu, ended = run_coupled(params, args.t_end, args.step, charge,
                                                             outputs=("y", "in_contact"))
        if charge == "static":
            coupled_cpu = min([coupled_cpu] + [run_coupled(params, args.t_end, args.step, charge)[2]
                                               for _ in range(2)])
        n_steps = len(coupled_t) - 1
        print(f"{charge} model's charge fed back, {n_steps} communication steps of {args.step:g} s "
              f"to t = {coupled_t[-1]:.4g} s{' (the exit)' if ended else ''}: {coupled_cpu:.3g} s "
              f"CPU against {plain_cpu:.3g} s uncoupled (the same steps, F_N_ext never set): ratio "
              f"{coupled_cpu / plain_cpu:.3g}, {1e6 * (coupled_cpu - plain_cpu) / n_steps:.3g} us "
              f"more per step")
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    ax1.plot(1e3 * plain_t, [1e3 * r["y"] for r in plain], lw=0.8, label="uncoupled")
    ax1.plot(1e3 * coupled_t, [1e3 * r["y"] for r in coupled], lw=0.8, label="image force fed back")
    ax1.set_ylabel("centre's height y [mm]")
    ax2.plot(1e3 * coupled_t[:-1], [-r["F_N_ext"] for r in coupled[:-1]], lw=0.8,
             label="image force (pull towards the chute)")
    weight = density * math.pi * si_defaults["semi_major_axis"] ** 2 * si_defaults["epsilon"] \
        * 9.81 * math.cos(si_defaults["tilt"])
    ax2.axhline(weight, color="k", ls="--", lw=0.8, label="weight per length m′ g cos β")
    ax2.set_yscale("log")
    ax2.set_ylabel("force per length [N/m]")
    ax2.set_xlabel("time [ms]")
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    ax1.set_title(f"reference case, {args.charge} model's charge, loop closed every "
                  f"{1e3 * args.step:g} ms", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "coupled.png"), dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
