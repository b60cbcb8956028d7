"""What every figure of the package shares: the axis labels that say what a quantity is
normalised by, colours that tell lines apart, a legend on each panel."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TAU_LABEL = "τ = t / sqrt(m/k)"
CHARGE_LABELS = {
    # model.md section 5a: q_i = sigma_i / sigma0, Q_static their mean
    "static": "static Q / Q_saturation  (mean σ_i / σ0)",
    # model.md section 5b: Q_sliding = mean Sigma_i / Sigma0 at the start; above 1 where
    # the frictional work has raised the saturation density
    "sliding": "sliding Q / Q_saturation at rest  (mean Σ_i / Σ0)",
}
SHORT_CHARGE_LABELS = {"static": "static Q / Q_sat", "sliding": "sliding Q / Q_sat at rest"}


def charge_label(model: str) -> str:
    """The axis label of a charge model's mean charge Q_<model>: what it is normalised by
    where the package knows it (CHARGE_LABELS), else its name."""
    return CHARGE_LABELS.get(model, f"{model} Q  (mean over the segments)")

EPSILON_LABEL = "roundness ε = b/a"
HEIGHT_LABEL = "height of the centre Y / a"


def distinct_colours(n: int) -> list:
    """n colours that a reader tells apart: tab10 up to 10, tab20 up to 20, then a
    continuous map."""
    if n <= 10:
        return [plt.get_cmap("tab10")(i) for i in range(n)]
    if n <= 20:
        return [plt.get_cmap("tab20")(i) for i in range(n)]
    cmap = plt.get_cmap("turbo")
    return [cmap(0.05 + 0.9 * i / (n - 1)) for i in range(n)]


def legend(ax, handles=None, labels=None, outside=False, **kwargs):
    """A legend on this panel: readable, beside it (outside=True) or where it covers least."""
    options = dict(fontsize=8, framealpha=0.85)
    if outside:
        options.update(loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    options.update(kwargs)
    if handles is None:
        return ax.legend(**options)
    return ax.legend(handles, labels, **options)


def save(fig, path: str, dpi: int = 100) -> str:
    fig.savefig(path, dpi=dpi)
    plt.close(fig)
    return path
