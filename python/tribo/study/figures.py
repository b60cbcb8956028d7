"""The study's figures (PNG), one file per quantity, low and high friction side by side;
the bounce and charge figures with a row per normal dashpot when the study compares
dashpots. Every panel has its legend.

    bounce_amplitude.png   upper envelope of Y against tau, one line per epsilon
    charge_vs_time.png     Q_static and Q_sliding against tau, one line per epsilon
    charge_vs_epsilon.png  Q_static and Q_sliding against epsilon at the report times
    contact_modes.png      mode fractions (after the warm-up), contact fraction and turns
                           against epsilon
    trajectory.png         height of the centre and orientation against tau, a few epsilon
    segment_charge.png     each segment's charge at the end around the perimeter (polar),
                           a few epsilon (needs the segment charges: an FMI 3.0 FMU)
    transition.png         turns against epsilon at every point of the eps_t search, and
                           the final bracket
"""

import os

import numpy as np
from matplotlib.lines import Line2D

from ..batch.summary import (ENVELOPE_WIDTH, MOTION_CLASSES, REPORT_FRACTIONS, TURNED_OVER,
                             WARMUP, bounce_envelope, charge_column, report_times)
from ..plotting import (CHARGE_LABELS, EPSILON_LABEL, HEIGHT_LABEL, SHORT_CHARGE_LABELS, TAU_LABEL,
                        distinct_colours, legend, plt, save)
from .paper import FRICTION_TITLES, dashpot_name

FIGURES = ["bounce_amplitude.png", "charge_vs_time.png", "charge_vs_epsilon.png",
           "contact_modes.png", "trajectory.png", "segment_charge.png", "transition.png"]
MOTION_CLASS_COLOURS = {"flight": "tab:gray", "rocking": "tab:blue", "rolling": "tab:green",
                "tumbling": "tab:red", "bouncing": "tab:orange"}
CHARGE_MODELS = ("static", "sliding")
# the trajectory and the segment map show a few roundness values, not the whole grid
FEW = 4


def write_all(result, out_dir: str) -> list[str]:
    """Write every figure the result has the data for; returns their paths."""
    writers = {"bounce_amplitude.png": bounce_amplitude, "charge_vs_time.png": charge_vs_time,
               "charge_vs_epsilon.png": charge_vs_epsilon, "contact_modes.png": contact_modes,
               "trajectory.png": trajectory, "segment_charge.png": segment_charge,
               "transition.png": transition}
    paths = []
    for name in FIGURES:
        fig = writers[name](result)
        if fig is not None:
            paths.append(save(fig, os.path.join(out_dir, name)))
    return paths


def few_epsilons(epsilons, n: int = FEW) -> list:
    """n values spread over the grid, its ends included."""
    eps = sorted(epsilons)
    if len(eps) <= n:
        return eps
    return [eps[i] for i in sorted({round(k * (len(eps) - 1) / (n - 1)) for k in range(n)})]


def _panels(result, rows, width=6.0, height=3.6, **kwargs):
    frictions = result.settings.frictions
    fig, axes = plt.subplots(rows, len(frictions), figsize=(width * len(frictions), height * rows),
                             squeeze=False, layout="constrained", **kwargs)
    return fig, axes, frictions


def _title(result, what, friction, dashpot=None):
    """The panel's title: what it shows, the friction case, and the dashpot when the study
    compares dashpots."""
    title = f"{what}, {FRICTION_TITLES[friction]} friction"
    if dashpot is not None and len(result.settings.dashpots) > 1:
        title += f"\ndashpot on the {dashpot_name(dashpot)}"
    return title


def _lines_per_epsilon(result, rows, y_of, ylabel_of, what_of, epsilons=None, log=False):
    """The shape the time-series figures share: a panel per (row, friction), a line per
    epsilon of y_of(series, row) against tau. rows: (row key, dashpot) pairs."""
    fig, axes, frictions = _panels(result, len(rows), width=6.8)
    epsilons = epsilons or result.settings.epsilons
    colours = dict(zip(epsilons, distinct_colours(len(epsilons))))
    for i, (key, dashpot) in enumerate(rows):
        for j, friction in enumerate(frictions):
            ax = axes[i][j]
            for e in epsilons:
                s = result.series_of(dashpot, friction, e)
                ax.plot(s["time"], y_of(s, key), color=colours[e], lw=1, label=f"ε = {e:g}")
            if log:
                ax.set_yscale("log")
            ax.set_title(_title(result, what_of(key), friction, dashpot), fontsize=10)
            ax.set_xlabel(TAU_LABEL)
            ax.set_ylabel(ylabel_of(key))
            ax.grid(alpha=0.3)
            legend(ax, outside=True, ncol=1 if len(epsilons) <= 6 else 2, fontsize=7)
    return fig


def _model_rows(result):
    """(charge model, dashpot) for each row of the charge figures."""
    return [(model, d) for d in result.settings.dashpots for model in CHARGE_MODELS]


def bounce_amplitude(result):
    rows = [(None, d) for d in result.settings.dashpots]
    # log: from a tenth (flat, thin) to tens (tumbling) of the semi-major axis
    return _lines_per_epsilon(
        result, rows, lambda s, _: bounce_envelope(s),
        lambda _: f"upper envelope of Y / a (max over {ENVELOPE_WIDTH:g} τ)",
        lambda _: "bounce amplitude", log=True)


def charge_vs_time(result):
    return _lines_per_epsilon(
        result, _model_rows(result), lambda s, model: s[f"Q_{model}"],
        lambda model: CHARGE_LABELS[model], lambda model: f"{model} charge")


def charge_vs_epsilon(result):
    rows = _model_rows(result)
    fig, axes, frictions = _panels(result, len(rows))
    times = report_times(result.settings.t_end)
    colours = distinct_colours(len(times))
    for i, (model, d) in enumerate(rows):
        for j, friction in enumerate(frictions):
            ax = axes[i][j]
            runs = result.runs_of(d)
            runs = runs[runs.friction == friction].sort_values("epsilon")
            for k, (f, t) in enumerate(zip(REPORT_FRACTIONS, times)):
                ax.plot(runs["epsilon"], runs[charge_column(model, f)], "o-", ms=4,
                        color=colours[k], label=f"τ = {t:g}")
            ax.set_title(_title(result, f"{model} charge against roundness", friction, d), fontsize=10)
            ax.set_xlabel(EPSILON_LABEL)
            ax.set_ylabel(CHARGE_LABELS[model])
            ax.grid(alpha=0.3)
            legend(ax, outside=True)
    return fig


def contact_modes(result):
    fig, axes, frictions = _panels(result, 2)
    for j, friction in enumerate(frictions):
        runs = result.runs[result.runs.friction == friction].sort_values("epsilon")
        eps = runs["epsilon"].to_numpy()
        width = 0.8 * (np.min(np.diff(eps)) if len(eps) > 1 else 0.1)
        ax = axes[0][j]
        bottom = np.zeros(len(eps))
        for m in MOTION_CLASSES:
            f = runs[f"fraction_{m}_after_warmup"].to_numpy()
            ax.bar(eps, f, width, bottom=bottom, color=MOTION_CLASS_COLOURS[m], label=m)
            bottom += f
        ax.set_title(_title(result, f"motion classes after τ = {WARMUP:g}", friction), fontsize=10)
        ax.set_xlabel(EPSILON_LABEL)
        ax.set_ylabel("fraction of the time")
        ax.set_ylim(0, 1.02)
        legend(ax, outside=True)

        ax = axes[1][j]
        contact, = ax.plot(eps, runs["contact_fraction"], "o-", color="black")
        ax.set_ylim(0, 1.05)
        ax.set_xlabel(EPSILON_LABEL)
        ax.set_ylabel("contact fraction")
        twin = ax.twinx()
        turns, = twin.semilogy(eps, np.maximum(runs["turns"], 1e-4), "s--", color="tab:purple")
        twin.set_ylabel(f"turns |φ − φ0| / 2π by τ = {result.settings.t_end:g}", color="tab:purple")
        ax.set_title(_title(result, "time in contact and turns made", friction), fontsize=10)
        ax.grid(alpha=0.3)
        # beside the panel, past the twin axis' label: inside, it would cover a line
        legend(ax, [contact, turns], ["contact fraction (left)", "turns (right, log)"],
               loc="upper left", bbox_to_anchor=(1.16, 1.0), borderaxespad=0.0)
    return fig


def trajectory(result):
    """Height and orientation against time for a few roundness values: how each moves."""
    epsilons = few_epsilons(result.settings.epsilons)
    d = result.settings.dashpot
    fig, axes, frictions = _panels(result, 2, width=6.8)
    colours = dict(zip(epsilons, distinct_colours(len(epsilons))))
    for j, friction in enumerate(frictions):
        for e in epsilons:
            s = result.series_of(d, friction, e)
            axes[0][j].plot(s["time"], s["Y"], color=colours[e], lw=0.8, label=f"ε = {e:g}")
            revolutions = (s["phi_deg"] - s["phi_deg"].iloc[0]) / 360.0
            axes[1][j].plot(s["time"], revolutions, color=colours[e], lw=1, label=f"ε = {e:g}")
        axes[0][j].set_yscale("log")
        axes[0][j].set_ylabel(HEIGHT_LABEL)
        axes[0][j].set_title(_title(result, "height of the centre", friction), fontsize=10)
        # symmetric log: a rocking particle's few degrees and a tumbling one's hundreds of
        # turns on one axis
        axes[1][j].set_yscale("symlog", linthresh=0.01)
        axes[1][j].set_ylabel("orientation (φ − φ0) / 2π  [revolutions]")
        axes[1][j].set_title(_title(result, "orientation", friction), fontsize=10)
        for ax in axes[:, j]:
            ax.set_xlabel(TAU_LABEL)
            ax.grid(alpha=0.3)
            legend(ax, outside=True)
    return fig


def segment_charge(result):
    """Each segment's charge at the end, around the perimeter: the angle is the position
    along the boundary (arc length, 0 at the end of the long axis, 90 degrees at the end
    of the short axis, anticlockwise in the body frame, model.md section 5)."""
    d = result.settings.dashpot
    epsilons = few_epsilons(result.settings.epsilons)
    frictions = result.settings.frictions
    if any(result.segments_of(d, f, e) is None for f in frictions for e in epsilons):
        return None  # an FMI 2.0 FMU: no segment arrays
    fig, axes = plt.subplots(len(CHARGE_MODELS), len(frictions), figsize=(6.6 * len(frictions), 10),
                             squeeze=False, subplot_kw={"projection": "polar"}, layout="constrained")
    colours = dict(zip(epsilons, distinct_colours(len(epsilons))))
    for i, model in enumerate(CHARGE_MODELS):
        for j, friction in enumerate(frictions):
            ax = axes[i][j]
            for e in epsilons:
                q = result.segments_of(d, friction, e)[model].to_numpy()
                angle = 2 * np.pi * (np.arange(len(q) + 1) + 0.5) / len(q)  # closed curve
                ax.plot(angle, np.append(q, q[0]), color=colours[e], lw=1.2, label=f"ε = {e:g}")
            ax.set_title(f"{SHORT_CHARGE_LABELS[model]} per segment at τ = {result.settings.t_end:g}"
                         f"\n{FRICTION_TITLES[friction]} friction", fontsize=10, pad=14)
            ax.set_xticks(np.radians([0, 90, 180, 270]))
            ax.set_xticklabels(["long axis\n(tip)", "short axis", "tip", "short axis\n(lies on the plate at φ = 0)"],
                               fontsize=7)
            ax.tick_params(axis="y", labelsize=7)
            legend(ax, loc="upper left", bbox_to_anchor=(1.12, 1.0), fontsize=8)
    fig.suptitle("each segment's charge around the perimeter: angle = arc length from the end of "
                 "the long axis, anticlockwise; radius = the segment's charge", fontsize=10)
    return fig


def transition(result):
    fig, axes, frictions = _panels(result, 1)
    for j, friction in enumerate(frictions):
        ax = axes[0][j]
        pts = result.transition_points[result.transition_points.friction == friction] \
            .sort_values("epsilon")
        turned = pts["turned_over"].astype(bool)
        y = np.maximum(pts["turns_max"].to_numpy(), 1e-4)
        ax.semilogy(pts["epsilon"], y, "-", color="lightgray", zorder=1)
        for grid, marker in ((True, "o"), (False, "x")):
            sel = (pts["on_grid"] == grid).to_numpy()
            for turn, colour in ((True, "tab:red"), (False, "tab:blue")):
                k = sel & (turned == turn).to_numpy()
                ax.semilogy(pts["epsilon"][k], y[k], marker, color=colour, ls="none",
                            label=f"{'grid' if grid else 'refinement'}: "
                                  f"{'turns over' if turn else 'does not'}")
        ax.axhline(TURNED_OVER, color="black", lw=0.8, ls=":")
        handles, labels = ax.get_legend_handles_labels()
        handles.append(Line2D([], [], color="black", lw=0.8, ls=":"))
        labels.append(f"turned over: {TURNED_OVER:g} turn")
        t = result.transitions[friction]
        if t.found:
            span = ax.axvspan(t.lo, t.hi, color="gold", alpha=0.5)
            handles.append(span)
            labels.append(f"ε_t = {t.estimate:.4f} ± {t.uncertainty:.4f}")
        ax.set_title(_title(result, "turning over", friction), fontsize=10)
        ax.set_xlabel(EPSILON_LABEL)
        ax.set_ylabel(f"most turns |φ − φ0| / 2π up to τ = {result.settings.t_end:g}")
        ax.grid(alpha=0.3, which="both")
        legend(ax, handles, labels, fontsize=7, outside=True)
    return fig
