"""The figure of a charge-per-impact map: for each charge model (a row), the charge per
impact against the impact angle (at the map's highest speed) and against the impact speed
(at its most head-on angle), a line per roundness, each the mean over the orientations;
the title says the set-up (materials, size, and whose the charges in C are: the
spheroid's, or the cylinder's of its depth with grain_geometry 0).
A point where some episode did not lift off (it came to rest on the plate, or was still in
contact at the time limit: its charge is of a sustained contact, not of an impact) is
ringed, with a legend entry that says so."""

from ..plotting import distinct_colours, legend, plt, save

CHARGE_UNIT, CHARGE_FACTOR = "pC", 1e12
SUSTAINED = "did not lift off (at rest or at the time limit)"


def write_impact_figure(table, models, path: str, title: str) -> str:
    """table: the map (impact_map.csv); models: its charge models (a row each)."""
    return save(impact_figure(table, models, title), path)


def impact_figure(table, models, title: str):
    """The figure (see the module's text), its legends beside the panels."""
    epsilons = sorted(table["epsilon"].unique())
    colours = distinct_colours(len(epsilons))
    top_speed, top_angle = table["speed"].max(), table["angle_deg"].max()
    n_phi = table["phi0_deg"].nunique()
    fig, axes = plt.subplots(len(models), 2, figsize=(14, 4.5 * len(models)),
                             layout="constrained", squeeze=False)
    for row, model in zip(axes, models):
        column = f"charge_{model}"
        for ax, x, fixed, fixed_value, unit in ((row[0], "angle_deg", "speed", top_speed, "m/s"),
                                                (row[1], "speed", "angle_deg", top_angle, "deg")):
            for colour, eps in zip(colours, epsilons):
                g = table[(table["epsilon"] == eps) & (table[fixed] == fixed_value)]
                mean = g.groupby(x)[column].mean().abs() * CHARGE_FACTOR
                ax.plot(mean.index, mean.to_numpy(), "o-", ms=4, color=colour, label=f"ε = {eps:g}")
                held = g.groupby(x)["lifted_off"].min() == 0
                if held.any():
                    ax.plot(mean.index[held.to_numpy()], mean.to_numpy()[held.to_numpy()], "o",
                            ms=10, mfc="none", mec="black", label=SUSTAINED)
            ax.set_xlabel({"angle_deg": "impact angle from the plate's surface (deg; 90: head-on)",
                           "speed": "impact speed (m/s)"}[x])
            ax.set_ylabel(f"|charge| per impact, {model} model ({CHARGE_UNIT})")
            name = {"speed": "speed", "angle_deg": "angle"}[fixed]
            ax.set_title(f"{model} model, {name} = {fixed_value:g} {unit}, mean over "
                         f"{n_phi} orientation{'s' if n_phi > 1 else ''}", fontsize=10)
            ax.grid(alpha=0.3)
            handles, labels = ax.get_legend_handles_labels()
            once = dict(zip(labels, handles))  # the ring's entry once, after the lines
            order = sorted(once, key=lambda label: label == SUSTAINED)
            legend(ax, [once[label] for label in order], order, outside=True)
    fig.suptitle(title)
    return fig
