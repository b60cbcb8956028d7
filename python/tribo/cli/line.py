"""tribo line: grains through the separation line, the SI chute and then the free-fall
separator from the chute's exit state (docs/line.md): one grain, a binary mixture at one
voltage, or a mixture's voltage sweep with grade and recovery.

    tribo line grain --particle nylon --voltage 30e3
    tribo line mixture -n 1000 --seed 1 --voltage 30e3 --out out/line-mixture
    tribo line sweep -n 1000 --seed 1 --voltages 5e3:40e3:8 --workers 2 --out out/line-sweep
    tribo line sweep -n 200 --particles PE,nylon --fraction 0.3 --splitter -0.005 --out out/line-30

grain prints the grain's exit from the chute and its landing (or that it came to rest on
the chute, or was still on it at the horizon --t-end: it never enters the separator).
mixture and sweep draw n
grains from the feed of tribo population (the reference case's: shapes 0.3-1, sizes
0.2-2 mm, on 0.3 m of steel tilted 30 degrees), the two materials of --particles (default
PE and nylon, which charge negatively and positively on steel) by their mass fraction
(--fraction of the first, default 0.5), each grain entering the separator at a point drawn
across --feed-width (m, default 0.01). The chute runs once per grain with one charge model
(--charge-model: static, the default, or another of the SI FMU's charge models, such as
sliding: alternative laws of the same charge), the separator once per voltage. The products split at --splitter (m, default 0,
the centre line between the bins of the two plates' sides). Separator settings (gap,
height, n_bins, air_density, ...) by --separator NAME=VALUE, chute parameters by --set.

Writes into --out: particles.csv (a row per grain: material, chute results, q/m, mass, the
landing at the first voltage), landings.csv (a row per grain and voltage), line.csv (a row
per voltage: masses per material in each product, on each plate, not collected, and the
grains that stayed on the chute, at rest or at the horizon, by count and mass; grade and
recovery of each product), bins.csv, line.png (a sweep), line.json; the closing line says
per material how many grains stayed on the chute. An interrupted run resumes when the same
command is run again. Dask: as tribo population.
"""

import math
import os

from ..batch.specs import check_count
from ..line.defaults import DEFAULT_FEED_WIDTH, DEFAULT_PAIR
from ..populations.feed_variables import DEFAULT_CHUTE
from .common import (INPUT_ERRORS, add_job_options, add_materials_option, add_out_option,
                     add_vibration_option, fail, name_value, one_line, run_job, vibration_of)

VOLTAGE_DEFAULT = 30e3


def voltages_of(text: str) -> list[float]:
    """LOW:HIGH:N (N values from LOW to HIGH) or V1,V2,..."""
    parts = text.split(":")
    try:
        if len(parts) == 3:
            lo, hi, n = float(parts[0]), float(parts[1]), int(parts[2])
            if n < 1:
                raise ValueError
        else:
            values = [float(v) for v in text.split(",")]
    except ValueError:
        raise ValueError(f"--voltages {text}: expected LOW:HIGH:N or V1,V2,... in V") from None
    if len(parts) != 3:
        return values
    check_count(n, f"--voltages {text}: the number of voltages")
    return [lo] if n == 1 else [lo + (hi - lo) * i / (n - 1) for i in range(n)]


def add_arguments(p) -> None:
    p.add_argument("mode", choices=("grain", "mixture", "sweep"),
                   help="one grain, a mixture at one voltage, or a mixture's voltage sweep")
    p.add_argument("-n", "--grains", type=int, default=200, help="grains of a mixture (default 200)")
    p.add_argument("--seed", type=int, default=0, help="the draw's seed (default 0)")
    p.add_argument("--particle", default="PE", help="grain: the particle material (default PE)")
    p.add_argument("--particles", default=",".join(DEFAULT_PAIR),
                   help="mixture: the two materials A,B (default PE,nylon)")
    p.add_argument("--fraction", type=float, default=0.5,
                   help="mixture: mass fraction of A (default 0.5)")
    p.add_argument("--wall", default="steel", help="the chute's material (default steel)")
    p.add_argument("--voltage", type=float, default=VOLTAGE_DEFAULT,
                   help="grain, mixture: the electrode voltage U, V (default 30e3)")
    p.add_argument("--voltages", default="5e3:40e3:8",
                   help="sweep: LOW:HIGH:N or V1,V2,... in V (default 5e3:40e3:8)")
    p.add_argument("--size", type=float, default=1e-3, help="grain: long diameter 2a, m (default 1e-3)")
    p.add_argument("--epsilon", type=float, default=0.6, help="grain: roundness b/a (default 0.6)")
    p.add_argument("--phi0-deg", type=float, default=0.0,
                   help="grain: orientation of the long axis at the drop, degrees (default 0)")
    p.add_argument("--x-entry", type=float, default=0.0, help="grain: entry across the gap, m (default 0)")
    p.add_argument("--feed-width", type=float, default=DEFAULT_FEED_WIDTH,
                   help=f"mixture: width of the feed across the gap, m (default {DEFAULT_FEED_WIDTH:g})")
    p.add_argument("--splitter", type=float, default=0.0,
                   help="mixture: the products' splitter across the gap, m (default 0)")
    p.add_argument("--charge-model", default="static", metavar="MODEL",
                   help="the chute's one charge model, one of the SI FMU's (default static; "
                        "sliding)")
    p.add_argument("--chute-length", type=float, default=DEFAULT_CHUTE["chute_length"],
                   help=f"m (default {DEFAULT_CHUTE['chute_length']:g})")
    p.add_argument("--tilt-deg", type=float, default=DEFAULT_CHUTE["tilt_deg"],
                   help=f"degrees (default {DEFAULT_CHUTE['tilt_deg']:g})")
    add_vibration_option(p)
    p.add_argument("--set", type=name_value, action="append", default=[], metavar="NAME=VALUE",
                   help="any other SI chute parameter by the package's names")
    p.add_argument("--separator", type=name_value, action="append", default=[],
                   metavar="NAME=VALUE", help="a separator setting (gap, height, n_bins, ...)")
    p.add_argument("--t-end", type=float, default=5.0, help="the chute's horizon, s (default 5)")
    add_materials_option(p)
    add_out_option(p, os.path.join("out", "line"))
    p.add_argument("--fmu", help="the SI chute FMU (default: the build's tribo_si_fmi3.fmu)")
    p.add_argument("--separator-fmu", help="the separator FMU (default: the build's "
                                           "tribo_separator_fmi3.fmu)")
    add_job_options(p)
    p.add_argument("--no-plot", action="store_true", help="no figure")


def chute_of(args) -> dict:
    return {"chute_length": args.chute_length, "tilt_deg": args.tilt_deg, **vibration_of(args)}


def check_finite(args, names) -> None:
    for name in names:
        if not math.isfinite(getattr(args, name)):
            raise ValueError(f"--{name.replace('_', '-')} {getattr(args, name)}: a finite number")


def run_grain(args) -> int:
    # the job's modules (and numpy, pandas, fmpy) once it runs: --help and a mistake in the
    # options need none of them (common.py)
    from ..fmu.names import format_number
    from ..line.grain import check_separator, load_images, run_line_grain  # the same
    from ..line.mixture import Line, check_line, line_specs  # the same
    check_finite(args, ("size", "epsilon", "phi0_deg", "x_entry", "voltage"))
    line = Line((args.particle,), args.wall, distributions={"epsilon": args.epsilon, "size": args.size,
                                                          "phi0_deg": args.phi0_deg},
                chute=chute_of(args), settings=dict(args.set), separator=dict(args.separator),
                feed_width=0.0, charge_model=args.charge_model, materials=args.materials)
    images = load_images(args.fmu, args.separator_fmu, line.separator, [args.voltage])
    specs = line_specs(line, 1, 0, args.t_end, images.models)
    specs[0].params["x_entry"] = args.x_entry
    check_line(line, specs, images)
    check_separator(images.separator, dict(line.separator, x_entry=args.x_entry),
                    [args.voltage], [args.size])
    r = run_line_grain(images, specs[0]).row
    if not r["exited"]:
        why = (f"came to rest on the chute at {r['rest_time']:.6g} s" if r["at_rest"] == 1
               else f"was still on the chute at the horizon of {format_number(args.t_end)} s"
               if r["end_reason"] == 0
               else f"did not leave the chute within {format_number(args.t_end)} s")
        print(f"line: the grain {why}: it does not enter the separator (q/m = "
              f"{r['charge_to_mass']:.4g} C/kg, {args.charge_model} model)")
        return 0
    print(f"line: {line.particles[0]} on {args.wall}, size {format_number(args.size)} m: left "
          f"the chute at {r['time_end']:.6g} s, u = {r['u']:.4g} m/s, v = {r['v']:.4g} m/s, "
          f"q/m = {r['charge_to_mass']:.4g} C/kg ({args.charge_model} model), mass "
          f"{r['mass']:.4g} kg")
    if r["landed"]:
        where = f"landed in bin {r['bin']} at x = {r['x_end'] * 1e3:.4g} mm"
    elif r["electrode"]:
        where = (f"caught on the plate at {'+' if r['electrode'] > 0 else '-'}gap/2, "
                 f"z = {r['z_end'] * 1e3:.4g} mm")
    else:
        where = "still falling at the separator's horizon"
    print(f"line: at U = {format_number(args.voltage)} V it {where}, after "
          f"{r['flight_time']:.4g} s of flight (at {r['time_land']:.6g} s)")
    return 0


def job_of(args):
    from ..line.mixture import Line, LineJob  # the job's modules once it runs (run_grain)
    voltages = voltages_of(args.voltages) if args.mode == "sweep" else [args.voltage]
    bad = [v for v in voltages if not math.isfinite(v)]
    if bad:
        raise ValueError(f"voltage {bad[0]}: a finite number of V")
    check_finite(args, ("fraction", "feed_width", "splitter"))
    line = Line(tuple(p.strip() for p in args.particles.split(",")), args.wall, args.fraction,
                chute=chute_of(args), settings=dict(args.set), separator=dict(args.separator),
                feed_width=args.feed_width, charge_model=args.charge_model,
                splitter=args.splitter, materials=args.materials)
    line.check()
    if len(line.particles) != 2:
        raise ValueError(f"--particles {args.particles}: two materials A,B")
    return LineJob("mixture", line, args.grains, args.seed, args.t_end, voltages, args.fmu,
                   args.separator_fmu, figure=not args.no_plot)


def told(job, report) -> list[str]:
    from ..line.mixture import stayed_text  # loaded by the job that made the report
    from ..materials import material  # the same
    lines = [f"line: {report.executed} grains run, {report.skipped} already in the file, "
             f"{len(report.failed)} failed"]
    if report.table is not None:
        cols = ["voltage"] + [c for c in report.table.columns
                              if c.startswith(("grade_", "recovery_"))] + ["separation"]
        materials = [material(p, "particle").key for p in job.line.particles]
        first = report.table.iloc[0]
        fed = sum(first[f"fed_{m}"] for m in materials)
        shares = ", ".join(f"{m} {first[f'fed_{m}'] / fed:.3g}" for m in materials) if fed > 0 else ""
        if sum(first[f"not_exited_{m}"] for m in materials) > 0:
            stayed = (f"line: {stayed_text(first, materials, job.t_end)}: these do not enter "
                      f"the separator (not collected: counted in the recovery's fed mass)")
        else:
            stayed = "line: every grain left the chute"
        best = report.table.loc[report.table["separation"].idxmax()] \
            if report.table["separation"].notna().any() else None
        lines += [report.table[cols].to_string(index=False, float_format=lambda v: f"{v:.4g}"),
                  f"line: separation = the recoveries' sum less 1: 0 for a random split of the "
                  f"feed, whose grades are the feed's mass shares ({shares}), 1 for a complete "
                  f"one; " + (f"{best['separation']:.3g} at {best['voltage']:g} V, the most"
                              if best is not None else "none: a material drew no grain"),
                  stayed, f"line: wrote {', '.join(report.files)}"]
    return lines


def run(args) -> int:
    if args.mode != "grain":
        return run_job(args, job_of, told)
    try:
        return run_grain(args)
    except INPUT_ERRORS as e:
        return fail(args.prog, one_line(e))
