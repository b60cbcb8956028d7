"""The study's tables: every number per run as CSV, the headline numbers as markdown.

    study_runs.csv          one row per (dashpot, friction, epsilon): parameters, charges
                            at the report times, contact statistics, mode fractions,
                            warnings, bounce amplitude, CPU and wall time of the run
    transition_points.csv   every roundness the eps_t search evaluated
    study.md                set-up, definitions, eps_t, the tables, timing, figures
"""

import math
import os

import pandas as pd

from ..batch.executors import available_cores
from ..batch.summary import (ENVELOPE_WIDTH, MOTION_CLASSES, REPORT_FRACTIONS, TURNED_OVER,
                             WARMUP, charge_column, report_times)
from .figures import FIGURES
from .paper import FRICTION_TITLES, dashpot_name


def markdown_table(df: pd.DataFrame, formats: dict | None = None) -> str:
    """A pipe table (pandas' to_markdown needs tabulate, which the project does not use)."""
    formats = formats or {}

    def cell(column, value):
        if isinstance(value, float) and math.isnan(value):
            return ""
        fmt = formats.get(column)
        return format(value, fmt) if fmt else str(value)

    lines = ["| " + " | ".join(df.columns) + " |", "|" + "---|" * len(df.columns)]
    for _, row in df.iterrows():
        lines.append("| " + " | ".join(cell(c, row[c]) for c in df.columns) + " |")
    return "\n".join(lines)


def charges_table(runs: pd.DataFrame, t_end: float) -> pd.DataFrame:
    out = runs[["friction", "epsilon"]].copy()
    for model in ("static", "sliding"):
        for f, t in zip(REPORT_FRACTIONS, report_times(t_end)):
            out[f"Q_{model} @{t:g}"] = runs[charge_column(model, f)]
    return out


MOTION_FORMATS = {"contact_fraction": ".3f", "turns": ".3g", "warnings": "d", "max delta_y / eps": ".3f",
                  "Y max": ".3f", "bounce amp.": ".3f", "CPU s": ".2f", "wall s": ".2f",
                  **{m: ".3f" for m in MOTION_CLASSES}}


def _add_motion(out: pd.DataFrame, runs: pd.DataFrame) -> pd.DataFrame:
    """The motion's columns of a run: contact, turns, mode fractions after the warm-up,
    warnings, indentation, height, bounce amplitude."""
    out["contact_fraction"] = runs["contact_fraction"]
    out["turns"] = runs["turns"]
    for m in MOTION_CLASSES:
        out[m] = runs[f"fraction_{m}_after_warmup"]
    out["warnings"] = runs["assumption_warnings"]
    out["max delta_y / eps"] = runs["delta_y_max"] / runs["epsilon"]
    out["Y max"] = runs["Y_max"]
    out["bounce amp."] = runs["bounce_amplitude_mean"]
    return out


def motion_table(runs: pd.DataFrame) -> pd.DataFrame:
    out = _add_motion(runs[["friction", "epsilon"]].copy(), runs)
    out["CPU s"] = runs["cpu_s"]
    out["wall s"] = runs["wall_s"]
    return out


COMPARISON_FORMATS = {**MOTION_FORMATS, "Q_static": ".4f", "Q_sliding": ".4f"}


def dashpot_table(result) -> pd.DataFrame:
    """The grid with every dashpot, the dashpots of one (friction, epsilon) on adjacent rows;
    the charges at the horizon."""
    s = result.settings
    runs = result.all_runs
    runs = runs.assign(_f=runs["friction"].map({f: i for i, f in enumerate(s.frictions)}),
                       _d=runs["damping_point"].map({d: i for i, d in enumerate(s.dashpots)}))
    runs = runs.sort_values(["_f", "epsilon", "_d"], kind="stable")
    out = runs[["friction", "epsilon"]].copy()
    out["dashpot"] = runs["damping_point"].map(dashpot_name)
    _add_motion(out, runs)
    for model in ("static", "sliding"):
        out[f"Q_{model}"] = runs[charge_column(model, 1.0)]
    out["CPU s"] = runs["cpu_s"]
    return out


def above_transition_note(result) -> str:
    """What the runs that turn over do (above eps_t, on the grid): how deep they indent,
    how often beyond the assumptions, how high they fly, how they move."""
    lines = []
    for friction, t in result.transitions.items():
        runs = result.runs
        g = runs[(runs["friction"] == friction) & (runs["epsilon"] >= t.hi)] if t.found else runs[:0]
        if not len(g):
            continue

        def span(values, fmt):
            lo, hi = values.min(), values.max()
            return format(lo, fmt) if lo == hi else f"{format(lo, fmt)} to {format(hi, fmt)}"

        per_time = g["assumption_warnings"].sum() / (len(g) * result.settings.t_end)
        lines.append(
            f"- {FRICTION_TITLES.get(friction, friction)}, the grid's {len(g)} run(s) above eps_t "
            f"(epsilon {span(g['epsilon'], 'g')}): largest recorded indentation "
            f"{span(g['delta_y_max'] / g['epsilon'], '.3f')} of epsilon; assumption warnings "
            f"{span(g['assumption_warnings'], 'd')} per run ({per_time:.2g} per unit time); "
            f"highest centre {span(g['Y_max'], '.3g')}; contact fraction "
            f"{span(g['contact_fraction'], '.3f')}; after the warm-up in flight "
            f"{span(g['fraction_flight_after_warmup'], '.3f')}, tumbling "
            f"{span(g['fraction_tumbling_after_warmup'], '.3f')}, rolling "
            f"{span(g['fraction_rolling_after_warmup'], '.3f')}, rocking "
            f"{span(g['fraction_rocking_after_warmup'], '.3f')}, bouncing "
            f"{span(g['fraction_bouncing_after_warmup'], '.3f')}.")
    return "\n".join(lines)


def transition_table(result) -> pd.DataFrame:
    rows = []
    checks = result.tolerance_checks
    for friction, t in result.transitions.items():
        c = checks[checks.friction == friction] if len(checks) else checks
        agree = bool(len(c)) and bool((c["turns_at_study_tolerance"] == c["turns_at_rtol_1e-10"]).all())
        rows.append({
            "friction": FRICTION_TITLES.get(friction, friction),
            "eps_t": f"{t.estimate:.4f} +- {t.uncertainty:.4f}" if t.found else t.describe(),
            "bracket (lo, hi]": f"({t.lo:.4f}, {t.hi:.4f}]" if t.found else "",
            "runs": len(t.evaluated),
            "monotonic on the grid": "yes" if t.monotonic_on_grid else "no",
            "monotonic, all points": "yes" if t.monotonic else "no",
            "ends agree at rtol 1e-10": ("yes" if agree else "no") if len(c) else "",
        })
    return pd.DataFrame(rows)


def assumptions_note(runs: pd.DataFrame) -> str:
    """Where the runs left the contact model's small-indentation assumption (measured)."""
    lines = []
    for friction, g in runs.groupby("friction", sort=False):
        ratio = g["delta_y_max"] / g["epsilon"]
        worst = g.loc[ratio.idxmax()]
        flagged = g[g["assumption_warnings"] > 0]
        turning = g[g["turned_over"] == 1]
        line = (f"- {FRICTION_TITLES.get(friction, friction)}: {len(flagged)} of {len(g)} runs have "
                f"assumption warnings (epsilon {', '.join(f'{e:g}' for e in flagged['epsilon']) or '-'}); "
                f"the largest recorded indentation is {ratio.max():.3f} of the semi-minor axis "
                f"(epsilon = {worst['epsilon']:g}).")
        if len(turning):
            line += (f" Of the runs that turn over, the highest centre height reached is "
                     f"{turning['Y_max'].min():.3f} to {turning['Y_max'].max():.3f} (a rigid ellipse "
                     f"turning over on the plate lifts its centre to 1, standing on its tip).")
        lines.append(line)
    return "\n".join(lines)


def tolerance_text(result) -> str:
    tol = result.tolerances
    given = dict(result.settings.tolerances)
    text = ", ".join(f"{name} = {value:g}" for name, value in tol.items())
    return text + (" (given)" if given else " (the FMU's defaults)")


def write_all(result, out_dir: str, command: str) -> list[str]:
    """study_runs.csv, transition_points.csv and study.md into out_dir (their paths)."""
    study_runs = os.path.join(out_dir, "study_runs.csv")
    result.all_runs.to_csv(study_runs, index=False)
    points = os.path.join(out_dir, "transition_points.csv")
    result.transition_points[["friction", "epsilon", "on_grid", "turns_max", "turned_over", "turns",
                              "contact_fraction", "key"]].sort_values(["friction", "epsilon"]) \
        .to_csv(points, index=False)
    md = (["# The paper's study through the FMU", "",
           f"Generated by `{command}`." if command else "", ""]
          + setup_section(result) + definitions_section(result) + results_sections(result)
          + dashpots_section(result) + run_time_section(result)
          + [f"![{name}]({name})" for name in figures_in(out_dir)])
    path = os.path.join(out_dir, "study.md")
    with open(path, "w") as f:
        f.write("\n".join(md) + "\n")
    return [study_runs, points, path]


def setup_section(result) -> list[str]:
    s = result.settings
    others = [dashpot_name(d) for d in s.dashpots[1:]]
    dashpot_text = (f"Normal dashpot on the {dashpot_name(s.dashpot)} (damping_point = {s.dashpot}, "
                    f"docs/model.md section 3)" +
                    (f"; the grid is run again with the dashpot on the {' and the '.join(others)} "
                     f"(damping_point = {', '.join(str(d) for d in s.dashpots[1:])}) for the "
                     f"comparison below; everything else is the first's." if others else "."))
    return [
        "## Set-up",
        "",
        f"docs/model.md section 7: Gamma = 0.001, beta = 45 deg, tau0 = tau_r = 1, Sigma0 = 0.01, "
        f"eta = 0.1, N = 2000 segments, drop speed 0.025, both charge models; mu = nu = 0.1 "
        f"(low friction) and 1.0 (high friction); epsilon in {{{', '.join(f'{e:g}' for e in s.epsilons)}}}; "
        f"tau from 0 to {s.t_end:g}, outputs recorded every {s.record_interval:g}. "
        f"Integrator: CVODE (Adams), {tolerance_text(result)}. {dashpot_text}",
        "",
    ]


def definitions_section(result) -> list[str]:
    s = result.settings
    return [
        "## Definitions",
        "",
        "- **Units** (docs/model.md section 1): lengths in semi-major axes a, time "
        "tau = t / sqrt(m/k) (m the mass, k the contact stiffness). Q_static is the mean of "
        "sigma_i / sigma0 over the segments: the static charge over its saturation charge. "
        "Q_sliding is the mean of Sigma_i / Sigma0: the sliding charge over the saturation "
        "charge at rest, above 1 where frictional work has raised the saturation density.",
        f"- **Bounce amplitude**: the upper envelope of the centre height Y: the maximum of the "
        f"recorded Y over a centred sliding window of {ENVELOPE_WIDTH:g} time units. The table "
        f"gives its mean over tau >= {WARMUP:g}.",
        f"- **Turns over**: |phi - phi0| reaches {TURNED_OVER:g} revolutions (pi: onto the other "
        f"side) at some recorded time up to tau = {s.t_end:g}.",
        f"- **eps_t**: the smallest roundness that turns over. Coarse grid (the study's epsilon), "
        f"then multi-section between the last non-turning and the first turning value, "
        f"{s.points_per_round} point(s) per round, until the bracket is at most {s.transition_width:g} wide; eps_t is "
        f"the bracket's midpoint +- half its width. The ends of each final bracket are re-run "
        f"at rtol = 1e-10, atol = 1e-12.",
        f"- **Mode fractions**: fraction of the time after the warm-up (tau >= {WARMUP:g}) in each "
        f"contact mode of the FMU's classification (`motion_class`); the FMU's own fractions "
        f"over the whole run, which count the warm-up as bouncing, are in study_runs.csv.",
        f"- **warnings**: the FMU's `assumption_warnings`, the number of times the indentation "
        f"exceeded 0.1 min(epsilon, rho_c).",
        "",
    ]


def results_sections(result) -> list[str]:
    """The transition roundness, the charges, the motion and the assumptions' sections."""
    s = result.settings
    runs = result.runs
    grid_turns = {f: ", ".join(f"{e:g}" for e in s.epsilons
                               if result.transitions[f].evaluated.get(round(e, 10)))
                  for f in result.transitions}
    charges, motion = charges_table(runs, s.t_end), motion_table(runs)
    return [
        "## Transition roundness",
        "",
        markdown_table(transition_table(result)),
        "",
        "Turning grid values: " + "; ".join(f"{f} friction: {v or 'none'}" for f, v in grid_turns.items()) + ".",
        "",
        "## Charges",
        "",
        markdown_table(charges, {c: ".4f" for c in charges.columns[2:]}),
        "",
        "## Motion",
        "",
        "Contact fraction and turns at the end of the run; mode fractions after the warm-up.",
        "",
        markdown_table(motion, MOTION_FORMATS),
        "",
        "## The contact model's assumptions",
        "",
        assumptions_note(runs),
        above_transition_note(result),
        "",
    ]


def dashpots_section(result) -> list[str]:
    """The grid with every dashpot side by side (none for one dashpot)."""
    s = result.settings
    if len(s.dashpots) < 2:
        return []
    return [
        "## The dashpots side by side",
        "",
        f"The grid with each dashpot, the two runs of one (friction, epsilon) on adjacent rows: "
        f"contact fraction and turns at the end, mode fractions after the warm-up, the "
        f"charges at tau = {s.t_end:g}, the run's CPU time.",
        "",
        markdown_table(dashpot_table(result), COMPARISON_FORMATS),
        "",
    ]


def run_time_section(result) -> list[str]:
    """How many runs, on what, in how much time; then the figures' heading."""
    cpu_total = result.all_runs["cpu_s"].sum()
    return [
        "## Run time",
        "",
        f"{result.total_runs} runs in all ({len(result.all_runs)} on the grid, the rest for eps_t "
        f"and the tolerance check); {result.executed} executed by this invocation on {result.executor}, "
        f"the others reused from runs/results.csv. Wall time of this invocation: "
        f"{result.wall_s:.1f} s (from the start of the command, Dask start-up included; the "
        f"machine has {available_cores()} cores). CPU time of the grid's runs: {cpu_total:.1f} s "
        f"in all. FMU: {result.fmu_name}, SHA-256 {result.fmu_sha256[:16]}...",
        "",
        "## Figures",
        "",
    ]


def figures_in(out_dir: str) -> list[str]:
    return [name for name in FIGURES if os.path.exists(os.path.join(out_dir, name))]
