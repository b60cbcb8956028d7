"""The study's figures (PNG), one file per quantity, low and high friction side by side;
the first three with a row per normal dashpot when the study compares dashpots.

    bounce_amplitude.png   upper envelope of Y against tau, one line per epsilon
    charge_vs_time.png     Q_static and Q_sliding against tau, one line per epsilon
    charge_vs_epsilon.png  Q_static and Q_sliding against epsilon at the report times
    contact_modes.png      mode fractions (after the warm-up), contact fraction and turns
                           against epsilon
    transition.png         turns against epsilon at every point of the eps_t search, and
                           the final bracket
"""

import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .summary import ENVELOPE_WIDTH, MODES, TURNED_OVER, WARMUP, bounce_envelope, report_times, \
    time_label  # noqa: E402
from .specs import dashpot_name  # noqa: E402
from .tables import FRICTION_TITLES  # noqa: E402

FIGURES = ["bounce_amplitude.png", "charge_vs_time.png", "charge_vs_epsilon.png",
           "contact_modes.png", "transition.png"]
MODE_COLOURS = {"flight": "tab:gray", "rocking": "tab:blue", "rolling": "tab:green",
                "tumbling": "tab:red", "bouncing": "tab:orange"}


def write_all(result, out_dir: str) -> list[str]:
    writers = [bounce_amplitude, charge_vs_time, charge_vs_epsilon, contact_modes, transition]
    paths = []
    for name, writer in zip(FIGURES, writers):
        fig = writer(result)
        path = os.path.join(out_dir, name)
        fig.savefig(path, dpi=100)
        plt.close(fig)
        paths.append(path)
    return paths


def _colours(epsilons):
    cmap = plt.get_cmap("viridis")
    lo, hi = min(epsilons), max(epsilons)
    return {e: cmap(0.9 * (e - lo) / (hi - lo) if hi > lo else 0.0) for e in epsilons}


def _panels(result, rows, sharey=False):
    frictions = result.settings.frictions
    fig, axes = plt.subplots(rows, len(frictions), figsize=(6.5 * len(frictions), 3.8 * rows),
                             squeeze=False, sharey=sharey)
    return fig, axes, frictions


def _dashpot_label(result, dashpot):
    """'' for a study of one dashpot; else which dashpot a panel shows."""
    if len(result.settings.dashpots) == 1:
        return ""
    return f"\ndashpot on the {dashpot_name(dashpot)}"


def bounce_amplitude(result):
    dashpots = result.settings.dashpots
    fig, axes, frictions = _panels(result, len(dashpots), sharey=True)
    colours = _colours(result.settings.epsilons)
    for i, d in enumerate(dashpots):
        for j, friction in enumerate(frictions):
            ax = axes[i][j]
            for e in result.settings.epsilons:
                s = result.series_of(d, friction, e)
                ax.plot(s["tau"], bounce_envelope(s), color=colours[e], lw=1, label=f"eps {e:g}")
            ax.set_yscale("log")  # from a tenth (flat, thin) to tens (tumbling) of the semi-major axis
            ax.set_title(f"bounce amplitude, {FRICTION_TITLES[friction]} friction"
                         f"{_dashpot_label(result, d)}", fontsize=10)
            ax.set_xlabel("tau")
            ax.set_ylabel(f"upper envelope of Y (max over {ENVELOPE_WIDTH:g})")
            ax.grid(alpha=0.3)
    axes[0][-1].legend(fontsize=7, ncol=2, loc="upper left", bbox_to_anchor=(1.01, 1))
    fig.tight_layout()
    return fig


def _model_rows(result):
    """(charge model, dashpot) for each row of the charge figures."""
    return [(model, d) for d in result.settings.dashpots for model in ("static", "sliding")]


def charge_vs_time(result):
    rows = _model_rows(result)
    fig, axes, frictions = _panels(result, len(rows))
    colours = _colours(result.settings.epsilons)
    for i, (model, d) in enumerate(rows):
        for j, friction in enumerate(frictions):
            ax = axes[i][j]
            for e in result.settings.epsilons:
                s = result.series_of(d, friction, e)
                ax.plot(s["tau"], s[f"Q_{model}"], color=colours[e], lw=1, label=f"eps {e:g}")
            ax.set_title(f"Q_{model}, {FRICTION_TITLES[friction]} friction{_dashpot_label(result, d)}",
                         fontsize=10)
            ax.set_xlabel("tau")
            ax.set_ylabel(f"Q_{model}")
            ax.grid(alpha=0.3)
    axes[0][-1].legend(fontsize=7, ncol=2, loc="upper left", bbox_to_anchor=(1.01, 1))
    fig.tight_layout()
    return fig


def charge_vs_epsilon(result):
    rows = _model_rows(result)
    fig, axes, frictions = _panels(result, len(rows))
    times = report_times(result.settings.t_end)
    cmap = plt.get_cmap("plasma")
    for i, (model, d) in enumerate(rows):
        for j, friction in enumerate(frictions):
            ax = axes[i][j]
            runs = result.runs_of(d)
            runs = runs[runs.friction == friction].sort_values("epsilon")
            for k, t in enumerate(times):
                ax.plot(runs["epsilon"], runs[f"Q_{model}_{time_label(t)}"], "o-",
                        color=cmap(0.85 * k / max(1, len(times) - 1)), label=f"tau = {t:g}")
            ax.set_title(f"Q_{model} against roundness, {FRICTION_TITLES[friction]} friction"
                         f"{_dashpot_label(result, d)}", fontsize=10)
            ax.set_xlabel("epsilon = b/a")
            ax.set_ylabel(f"Q_{model}")
            ax.grid(alpha=0.3)
    axes[0][-1].legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1))
    fig.tight_layout()
    return fig


def contact_modes(result):
    fig, axes, frictions = _panels(result, 2)
    for j, friction in enumerate(frictions):
        runs = result.runs[result.runs.friction == friction].sort_values("epsilon")
        eps = runs["epsilon"].to_numpy()
        width = 0.8 * (np.min(np.diff(eps)) if len(eps) > 1 else 0.1)
        ax = axes[0][j]
        bottom = np.zeros(len(eps))
        for m in MODES:
            f = runs[f"fraction_{m}_after_warmup"].to_numpy()
            ax.bar(eps, f, width, bottom=bottom, color=MODE_COLOURS[m], label=m)
            bottom += f
        ax.set_title(f"contact modes after tau = {WARMUP:g}, {FRICTION_TITLES[friction]} friction",
                     fontsize=10)
        ax.set_xlabel("epsilon = b/a")
        ax.set_ylabel("fraction of time")
        ax.set_ylim(0, 1.02)

        ax = axes[1][j]
        ax.plot(eps, runs["contact_fraction"], "o-", color="black", label="contact fraction")
        ax.set_ylim(0, 1.05)
        ax.set_xlabel("epsilon = b/a")
        ax.set_ylabel("contact fraction")
        twin = ax.twinx()
        twin.semilogy(eps, np.maximum(runs["turns"], 1e-4), "s--", color="tab:purple", label="turns")
        twin.set_ylabel(f"turns by tau = {result.settings.t_end:g}", color="tab:purple")
        ax.set_title(f"time in contact and turns made, {FRICTION_TITLES[friction]} friction",
                     fontsize=10)
        ax.grid(alpha=0.3)
    axes[0][-1].legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1))
    fig.tight_layout()
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
        t = result.transitions[friction]
        if t.found:
            ax.axvspan(t.lo, t.hi, color="gold", alpha=0.5,
                       label=f"eps_t = {t.estimate:.4f} +- {t.uncertainty:.4f}")
        ax.set_title(f"turning over, {FRICTION_TITLES[friction]} friction", fontsize=10)
        ax.set_xlabel("epsilon = b/a")
        ax.set_ylabel(f"max turns up to tau = {result.settings.t_end:g}")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7, loc="center left")
    fig.tight_layout()
    return fig
