"""The figure that sets a fed stream's q/m beside the dilute limit's, for the same draw of
grains (docs/dem.md): the histograms of -q/m (or q/m for a positive pair) of both, and each
grain's fed q/m against its dilute q/m (the line: equal; a cross: a fed grain that did not
leave by the chute's end)."""

import numpy as np

from ..plotting import legend, plt, save
from ..populations.plot import QM_FACTOR, QM_UNIT


def comparison_figure(dilute, fed, model: str = "static", title: str = ""):
    a = dilute.set_index("key")[f"charge_to_mass_{model}"]
    b = fed.set_index("key")[f"charge_to_mass_{model}"].reindex(a.index)
    sign = -1.0 if (a < 0).all() else 1.0
    x, y = sign * a.to_numpy() * QM_FACTOR, sign * b.to_numpy() * QM_FACTOR
    what = "−q/m" if sign < 0 else "q/m"
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5), layout="constrained")
    bins = np.linspace(min(x.min(), np.nanmin(y)), max(x.max(), np.nanmax(y)), 25)
    left.hist(x, bins, alpha=0.6, label=f"dilute (mean {x.mean():.3g} {QM_UNIT})")
    left.hist(y, bins, alpha=0.6, label=f"fed stream (mean {np.nanmean(y):.3g} {QM_UNIT})")
    left.set_xlabel(f"{what}, {model} model ({QM_UNIT})")
    left.set_ylabel("grains")
    legend(left)
    left_chute = fed.set_index("key")["exited"].reindex(a.index).to_numpy() == 1
    right.scatter(x[left_chute], y[left_chute], s=12, label="a grain (left by the chute's end)")
    if not left_chute.all():
        right.scatter(x[~left_chute], y[~left_chute], s=16, marker="x",
                      label="a grain of the fed stream that did not leave by the end")
    lo, hi = bins[0], bins[-1]
    right.plot([lo, hi], [lo, hi], "k--", lw=1, label="fed = dilute")
    right.set_xlabel(f"{what} in the dilute limit ({QM_UNIT})")
    right.set_ylabel(f"{what} in the fed stream ({QM_UNIT})")
    legend(right)
    if title:
        fig.suptitle(title)
    return fig


def write_comparison_figure(dilute, fed, path: str, model: str = "static", title: str = "") -> str:
    return save(comparison_figure(dilute, fed, model, title), path)
