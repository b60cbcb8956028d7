"""The figure of a parameter sweep's results: the charges at the horizon, the contact
fraction and the turns against the first swept parameter, a line per combination of the
other swept parameters (and per horizon, where the file holds several). A run that ended
before its horizon (it came to rest on the chute or left it: summary.py, END_OUTPUTS) is
ringed: its values are those where it ended; the title counts each way a run ended."""

import math

import numpy as np

from ..plotting import charge_label, distinct_colours, legend, plt, save
from .summary import charge_column, ends_text

ENDED = "ended early: its values there"
MOTION = [  # column, axis label, log scale
    ("contact_fraction", "contact fraction (time in contact / t_end)", False),
    ("turns_max", "most turns |φ − φ0| / 2π", True),
]


def quantities(results) -> list[tuple]:
    """(column, axis label, log scale) of each panel: the charge at the horizon of each
    charge model the rows hold (Q_<model>_end), then the motion's."""
    models = [c[2:-4] for c in results.columns if c.startswith("Q_") and c.endswith("_end")]
    return [(charge_column(m, 1.0), charge_label(m), False) for m in models] + MOTION


def write_sweep_figure(results, swept: list[str], path: str) -> str:
    """results: the sweep's rows (tribo.load_results); swept: the swept parameters, the
    first on the x axis."""
    x, others = swept[0], list(swept[1:])
    if results["t_end"].nunique() > 1:
        others.append("t_end")
    groups = list(results.groupby(others, sort=True)) if others else [((), results)]
    colours = distinct_colours(len(groups))
    panels = quantities(results)
    rows = math.ceil(len(panels) / 2)
    fig, axes = plt.subplots(rows, 2, figsize=(13, 4 * rows), squeeze=False, layout="constrained")
    for ax in axes.flat[len(panels):]:
        ax.set_visible(False)
    for ax, (column, label, log) in zip(axes.flat, panels):
        for colour, (values, g) in zip(colours, groups):
            g = g.sort_values(x)
            values = values if isinstance(values, tuple) else (values,)
            name = ", ".join(f"{n} = {v:g}" for n, v in zip(others, values)) or "all runs"
            y = g[column].to_numpy(float)
            y = np.maximum(y, 1e-4) if log else y
            ax.plot(g[x], y, "o-", ms=4, color=colour, label=name)
            if "end_reason" in g.columns:
                ended = (g["end_reason"].to_numpy(float) > 0)
                if ended.any():
                    ax.plot(g[x].to_numpy()[ended], y[ended], "o", ms=10, mfc="none",
                            mec="black", label=ENDED)
        if log:
            ax.set_yscale("log")
        ax.set_xlabel(x)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        handles, labels = ax.get_legend_handles_labels()
        once = dict(zip(labels, handles))  # the ring's entry once, after the lines
        order = sorted(once, key=lambda label: label == ENDED)
        legend(ax, [once[label] for label in order], order, fontsize=7, outside=True)
    horizons = ", ".join(f"{t:g}" for t in sorted(results["t_end"].unique()))
    title = f"sweep over {', '.join(swept)}: {len(results)} runs, at the horizon τ = {horizons}"
    ends = ends_text(results)
    if ends:
        title += f"\n{ends}"
    fig.suptitle(title, fontsize=10)
    return save(fig, path)
