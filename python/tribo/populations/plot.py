"""The figure of a population, drawn from its summary (summary.py: the charge models, the
class edges and the statistics) and its particles' rows (the points): for each charge
model (a row), the q/m histogram with the summary's mean and percentiles, q/m against
roundness (a colour per size class) and against size (a colour per shape class), and the
exit speed against the charge (a colour per shape class).

A population's q/m spans decades, so the panels use log axes of its magnitude, drawn with
the polarity of the pair: −q/m when every particle charges negatively (σ0 < 0), q/m when
positively. The mean and the percentiles are those of summary.csv, of the signed values,
each line labelled with its signed value: the figure's "5th percentile" is the CSV's p5
(for a negative pair the largest magnitude). Sizes are in m, as in the tables; legends sit
beside their panels, clear of the data.

The histogram stacks the grains by how their run ended (summary.py's `ends_of`): those that
left the chute, those that came to rest on it and those still on it at the horizon, each
with its count and share of the mass in the legend, where the rows say it; the exit speed
panel shows the grains that left only (the others have no exit)."""

import math
import os

import numpy as np
from matplotlib.ticker import FuncFormatter, LogLocator, MaxNLocator, NullFormatter

from ..plotting import distinct_colours, legend, plt, save
from .summary import AT_HORIZON, AT_REST, EXITED, classes_of, edges_of, ends_of, grain_mass

QM_UNIT, QM_FACTOR = "µC/kg", 1e6
CHARGE_UNIT, CHARGE_FACTOR = "pC", 1e12
MIN_BINS, MAX_BINS = 5, 50
MARKED = (("mean", "-.", "mean"), ("p5", ":", "5th percentile"), ("p50", "-", "median"),
          ("p95", "--", "95th percentile"))
# the stream's mass-weighted mean (summary.py: what a Faraday cup at the chute's end reads,
# the number to design on), drawn apart from the plain statistics of the grains
STREAM = ("stream_mean", "-", "tab:red", "stream mean (mass-weighted, the grains that left)")
# a panel's variable that varies by less than this, relative, carries no information: every
# grain has the same value to rounding (a single size, spheres, identical exits)
SAME = 1e-6
# the histogram's stacks: how a grain's run ended, its legend text and colour
ENDS = ((EXITED, "left the chute", "tab:blue"), (AT_REST, "at rest on the chute", "tab:orange"),
        (AT_HORIZON, "on the chute at the horizon", "tab:gray"))


def histogram_bins(n: int) -> int:
    """Bins of a histogram of n values: the square-root rule, within MIN_BINS..MAX_BINS."""
    return int(min(MAX_BINS, max(MIN_BINS, math.ceil(math.sqrt(max(n, 1))))))


def polarity(values) -> int:
    """-1 if no value is positive (a negatively charging pair), +1 if none is negative, 0
    for both signs."""
    v = np.asarray(values, dtype=float)
    if (v <= 0).all():
        return -1
    return 1 if (v >= 0).all() else 0


def _magnitude_label(sign: int, what: str) -> str:
    return {-1: f"−{what}", 1: what, 0: f"|{what}|"}[sign]


def _by_class(results, summary, grouping, column, unit):
    """(name, rows) of each class of a grouping, by the summary's edges."""
    edges = edges_of(summary, grouping)
    labels = classes_of(results[column], edges)
    groups = []
    for i, interval in enumerate(labels.cat.categories):
        lo, hi = edges[i], edges[i + 1]
        name = {"epsilon": f"ε {lo:.2f}–{hi:.2f}", "size": f"size {lo:.3g}–{hi:.3g} {unit}"}[column]
        groups.append((name, results[labels == interval]))
    return groups


def readable_log(axis) -> None:
    """A log axis's ticks, readable over any range: its minor ticks unlabelled (matplotlib
    labels them over less than a decade, 3×10⁻³4×10⁻³6×10⁻³ overlapping), and over less
    than 1.5 decades majors at 1, 2 and 5 of each decade as plain numbers (a decade's one
    label would be none)."""
    ax = axis.axes  # its limits, autoscaled to the data drawn (the view interval may not be yet)
    lo, hi = sorted(ax.get_xlim() if axis.axis_name == "x" else ax.get_ylim())
    if lo > 0 and hi < 30 * lo:
        locator = LogLocator(subs=(1.0, 2.0, 5.0))
        decades = range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1)
        if sum(lo <= m * 10.0 ** k <= hi for k in decades for m in (1, 2, 5)) < 2:
            # within a step of 1, 2, 5 (grains of one size): three ticks, as many digits
            # as tell them apart
            locator = MaxNLocator(nbins=3)
        axis.set_major_locator(locator)
        digits = max(3, 2 + math.ceil(-math.log10((hi - lo) / hi))) if hi > lo else 3
        axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.{digits}g}"))
    axis.set_minor_formatter(NullFormatter())


def varies(values) -> bool:
    """Whether the values differ by more than SAME of their magnitude (a panel against
    them carries information)."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    return len(v) > 1 and float(np.ptp(v)) > SAME * float(np.max(np.abs(v)))


def _scatter(ax, groups, colours, x, y, xlabel, ylabel, title, logx=False, logy=False,
             empty="no particles"):
    """A panel of y(g) against x(g), a colour and a legend entry per group; `empty` said
    in the panel where no group has a row (no log axis then: there is nothing to scale)."""
    if not sum(len(g) for _, g in groups):
        ax.text(0.5, 0.5, empty, transform=ax.transAxes, ha="center", va="center")
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=10)
        return
    for colour, (name, g) in zip(colours, groups):
        ax.scatter(x(g), y(g), s=10, color=colour, label=f"{name} ({len(g)})")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    if logx:
        ax.set_xscale("log")
        readable_log(ax.xaxis)
    if logy:
        ax.set_yscale("log")
        readable_log(ax.yaxis)
    else:  # values that differ in their last digits, written out: no offset to add
        ax.ticklabel_format(axis="y", useOffset=False)
    legend(ax, outside=True)


def _end_groups(results) -> tuple[list[tuple[str, str, np.ndarray]], bool]:
    """(legend text, colour, mask) of each way the grains' runs ended that some grain took,
    the text with the count and the share of the mass, and True; one group of every grain
    and False where every grain left or the rows do not say how the runs ended."""
    ends = ends_of(results)
    if ends is None or ends.isna().any() or (ends == EXITED).all():
        return [(f"{len(results)} particles", "tab:blue", np.ones(len(results), bool))], False
    mass = grain_mass(results)
    total = mass.sum() if mass is not None else np.nan
    groups = []
    for end, text, colour in ENDS:
        mask = (ends == end).to_numpy()
        if mask.any():
            share = f", {100 * mass[mask].sum() / total:.3g} % of the mass" \
                if mass is not None and total > 0 else ""
            groups.append((f"{int(mask.sum())} {text}{share}", colour, mask))
    return groups, True


def _histogram(ax, qm, model, stats, groups, told):
    """The q/m histogram of a charge model on a log axis of its magnitude, stacked by how the
    grains' runs ended (`groups`, `told`: _end_groups), with the mean and percentiles of the
    signed values (`stats`: the summary's row of all particles)."""
    sign = polarity(qm)
    shown = np.abs(qm.to_numpy(dtype=float)) * QM_FACTOR
    positive = shown[shown > 0]
    n_bins = histogram_bins(len(positive))
    if len(positive) and positive.max() > positive.min():
        bins = np.geomspace(positive.min(), positive.max(), n_bins + 1)
    elif len(positive):
        bins = np.geomspace(positive.min() / 1.5, positive.min() * 1.5, n_bins + 1)
    else:
        bins = n_bins
    stacks = [shown[mask & (shown > 0)] for _, _, mask in groups]
    labels = [text if told else f"{text}, {n_bins} bins" for text, _, _ in groups]
    ax.hist(stacks, bins=bins, stacked=True, color=[c for _, c, _ in groups], alpha=0.8,
            label=labels)
    if told:  # the stacks' entries say how the runs ended: the bins get one of their own
        ax.plot([], [], " ", label=f"{len(shown)} particles, {n_bins} bins")
    zero = len(shown) - len(positive)
    if zero:
        ax.plot([], [], " ", label=f"{zero} with q/m = 0 (not on the log axis)")
    for column, style, name in MARKED:
        value = stats[column] * QM_FACTOR
        if value != 0 and np.isfinite(value):
            ax.axvline(abs(value), color="black", ls=style, lw=1.2,
                       label=f"{name} {value:.3g} {QM_UNIT}")
    column, style, colour, name = STREAM
    value = stats.get(column, np.nan) * QM_FACTOR
    if value != 0 and np.isfinite(value):
        ax.axvline(abs(value), color=colour, ls=style, lw=2, label=f"{name} {value:.3g} {QM_UNIT}")
    ax.set_xscale("log")
    readable_log(ax.xaxis)
    ax.set_xlabel(f"{_magnitude_label(sign, 'q/m')}, {model} model ({QM_UNIT})")
    ax.set_ylabel("particles")
    title = f"q/m distribution, {model} model"
    ax.set_title(f"{title}, every grain where its run ended" if told else title, fontsize=10)
    legend(ax, outside=True)
    return sign


def _left_out(results, exited) -> tuple[list[str], list[str]]:
    """The scatter panels that carry information ("roundness", "size", "exit"), and in words
    why each other one is left out: every grain of one roundness (spheres), of one size, or
    leaving at one speed (to rounding: SAME)."""
    kept, why = [], []
    for panel, column, unit, what in (("roundness", "epsilon", "", "roundness ε"),
                                      ("size", "size", " m", "size")):
        if varies(results[column]):
            kept.append(panel)
        else:
            why.append(f"q/m against {panel} (every grain {what} {results[column].iloc[0]:.3g}{unit})")
    speeds = results.loc[exited, "exit_speed"]
    if varies(speeds):
        kept.append("exit")
    elif len(speeds):
        why.append(f"exit speed against charge (every grain left at {speeds.iloc[0]:.4g} m/s)")
    return kept, why


def population_figure(results, summary, title: str = ""):
    """results: the population's rows (one per particle); summary: its summary (summary.py).
    A scatter panel whose variable is the same for every grain is left out, the title's
    last line saying so (_left_out)."""
    models = list(dict.fromkeys(summary["model"]))
    shapes = _by_class(results, summary, "shape", "epsilon", "")
    sizes = _by_class(results, summary, "size", "size", "m")
    shape_colours = distinct_colours(len(shapes))
    size_colours = distinct_colours(len(sizes))
    overall = summary[summary["grouping"] == "all"].set_index("model")
    groups, told = _end_groups(results)
    ends = ends_of(results)
    left_only = ends is not None and not (ends == EXITED).all()
    exited = (ends == EXITED).to_numpy() if left_only else np.ones(len(results), bool)
    kept, why = _left_out(results, exited)
    # wide enough for the title's lines, with one panel left
    fig, axes = plt.subplots(len(models), 1 + len(kept), figsize=(max(14.0, 6.5 * (1 + len(kept))),
                                                                   5 * len(models)),
                             layout="constrained", squeeze=False)
    exits = [(name, g[ends[g.index] == EXITED] if left_only else g) for name, g in shapes]
    for row, model in zip(axes, models):
        sign = _histogram(row[0], results[f"charge_to_mass_{model}"], model, overall.loc[model],
                          groups, told)
        label = f"{_magnitude_label(sign, 'q/m')}, {model} model ({QM_UNIT})"
        qm_of = lambda g: g[f"charge_to_mass_{model}"].abs() * QM_FACTOR  # noqa: E731
        panels = dict(zip(kept, row[1:]))
        if "roundness" in panels:
            _scatter(panels["roundness"], sizes, size_colours, lambda g: g["epsilon"], qm_of,
                     "roundness ε = b/a", label, "q/m against roundness", logy=True)
        if "size" in panels:
            _scatter(panels["size"], shapes, shape_colours, lambda g: g["size"], qm_of,
                     "size, the long diameter 2a (m)", label, "q/m against size", logx=True,
                     logy=True)
        if "exit" in panels:
            _scatter(panels["exit"], exits, shape_colours,
                     lambda g: g[f"charge_{model}"].abs() * CHARGE_FACTOR, lambda g: g["exit_speed"],
                     f"{_magnitude_label(sign, 'charge')}, {model} model ({CHARGE_UNIT}, the "
                     f"grain's)", "speed at the exit (m/s)",
                     "exit speed against charge, the grains that left" if left_only
                     else "exit speed against charge", logx=True, empty="no grain left the chute")
        for ax in row:
            ax.grid(alpha=0.3)
    title = title or f"population of {len(results)} particles"
    if why:
        title += "".join(f"\nleft out, no information: {w}" for w in why)
    fig.suptitle(title)
    return fig


def population_title(described: dict, n: int, seed: int, where: str, head: str = "") -> str:
    """A population's figure title: `head` (what ran it, e.g. the DEM), n grains of the pair,
    the seed, `where` (the chute and how the runs ended), and what else changed the result:
    a materials file (`described["materials"]`, the feed's), a vibrating plate
    (`described["vibration"]`: amplitude m, frequency Hz)."""
    title = (f"{head}{n} particles of {described['particle']} on {described['wall']} (seed "
             f"{seed}), {where}")
    extra = []
    if described.get("materials"):
        extra.append(f"materials from {os.path.basename(described['materials'])}")
    if described.get("vibration"):
        amplitude, frequency = described["vibration"]
        extra.append(f"the chute vibrating {amplitude * 1e3:g} mm at {frequency:g} Hz")
    return title + (f"; {', '.join(extra)}" if extra else "")


def write_population_figure(results, summary, path: str, title: str = "") -> str:
    return save(population_figure(results, summary, title), path)
