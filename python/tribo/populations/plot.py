"""The figure of a population: for each charge model (a row), the q/m histogram, q/m against
roundness (a colour per size class) and against size (a colour per shape class), and the
exit speed against the charge (a colour per shape class). Charges are drawn as magnitudes
on log axes (their sign is sigma0's, the same for every particle of a pair), since a
population's q/m spans decades."""

import numpy as np

from ..plotting import distinct_colours, legend, plt, save
from .summary import class_edges, classes_of

QM_UNIT, QM_FACTOR = "µC/kg", 1e6
CHARGE_UNIT, CHARGE_FACTOR = "pC", 1e12
SIZE_UNIT, SIZE_FACTOR = "mm", 1e3


def _by_class(results, column, edges, unit_factor, unit):
    labels = classes_of(results[column], edges)
    groups = []
    for i, interval in enumerate(labels.cat.categories):
        lo, hi = edges[i] * unit_factor, edges[i + 1] * unit_factor
        name = {"epsilon": f"ε {lo:.2f}–{hi:.2f}", "size": f"size {lo:.2f}–{hi:.2f} {unit}"}[column]
        groups.append((name, results[labels == interval]))
    return groups


def _scatter(ax, groups, colours, x, y, xlabel, ylabel, title, logx=False, logy=False):
    """A panel of y(g) against x(g), a colour and a legend entry per group."""
    for colour, (name, g) in zip(colours, groups):
        ax.scatter(x(g), y(g), s=10, color=colour, label=f"{name} ({len(g)})")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    if logx:
        ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    legend(ax)


def write_population_figure(results, path: str, shape_edges=None, size_edges=None,
                            title: str = "") -> str:
    """results: the population's rows (one per particle)."""
    shapes = _by_class(results, "epsilon", class_edges(results["epsilon"], shape_edges), 1.0, "")
    sizes = _by_class(results, "size", class_edges(results["size"], size_edges), SIZE_FACTOR, SIZE_UNIT)
    shape_colours = distinct_colours(len(shapes))
    size_colours = distinct_colours(len(sizes))
    fig, axes = plt.subplots(2, 4, figsize=(20, 9), layout="constrained")
    for row, model in zip(axes, ("static", "sliding")):
        qm = results[f"charge_to_mass_{model}"].abs() * QM_FACTOR
        label = f"|q/m|, {model} model ({QM_UNIT})"
        ax = row[0]
        positive = qm[qm > 0]
        bins = np.geomspace(positive.min(), positive.max() * 1.0001, min(40, max(5, len(qm) // 10))) \
            if len(positive) else 10
        ax.hist(qm, bins=bins, color="tab:blue", alpha=0.8, label=f"{len(qm)} particles")
        ax.set_xscale("log")
        for p, style in ((5, ":"), (50, "-"), (95, "--")):
            ax.axvline(np.percentile(qm, p), color="black", ls=style, lw=1, label=f"{p}th percentile")
        ax.set_xlabel(label)
        ax.set_ylabel("particles")
        ax.set_title(f"q/m distribution, {model} model")
        legend(ax)
        qm_of = lambda g: g[f"charge_to_mass_{model}"].abs() * QM_FACTOR  # noqa: E731
        _scatter(row[1], sizes, size_colours, lambda g: g["epsilon"], qm_of,
                 "roundness ε = b/a", label, "q/m against roundness", logy=True)
        _scatter(row[2], shapes, shape_colours, lambda g: g["size"] * SIZE_FACTOR, qm_of,
                 f"size, long diameter 2a ({SIZE_UNIT})", label, "q/m against size", logy=True)
        _scatter(row[3], shapes, shape_colours, lambda g: g[f"charge_{model}"].abs() * CHARGE_FACTOR,
                 lambda g: g["exit_speed"],
                 f"|charge|, {model} model ({CHARGE_UNIT}, cylinder of the depth set)",
                 "speed at the exit (m/s)", "exit speed against charge", logx=True)
        for ax in row:
            ax.grid(alpha=0.3)
    fig.suptitle(title or f"population of {len(results)} particles")
    return save(fig, path)
