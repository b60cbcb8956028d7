"""What a process engineer reads off a population: the charge-to-mass distribution of each
charge model (count, mean, standard deviation, percentiles) over all particles, per shape
class (ranges of epsilon) and per size class (ranges of the long diameter), and what a
Faraday cup at the chute's end reads (docs/model.md section 8d): the stream of the grains
that leave the chute, its mass-weighted mean q/m (their charge over their mass) and the
mass-weighted spread of q/m about it, and the mass fraction that stays on the chute.

A grain that does not leave is counted apart, by why (docs/model.md section 3c): it came to
rest on the chute (the run ended there, `end_reason` at_rest) or it was still on it at the
horizon (`end_reason` running); the count of each and its share of the mass. n, mean, std
and the percentiles are of every grain's q/m where its run ended; the stream's are of the
grains that left only.

The summary is computed once, from the particles' rows, and holds the class edges (`low`,
`high`) with the statistics: the figure (plot.py) draws it, it does not compute them again."""

import math

import numpy as np
import pandas as pd

PERCENTILES = (5, 25, 50, 75, 95)
# the stream's: mass-weighted mean and standard deviation of q/m over the grains that left
# the chute (C/kg), the mass fraction that did not leave
STREAM_COLUMNS = ["stream_mean", "stream_std", "stayed"]
# how many grains left, came to rest on the chute, were still on it at the horizon; the
# mass fraction of the last two (their sum is `stayed`)
END_COLUMNS = ["n_exited", "n_at_rest", "n_at_horizon", "at_rest_fraction", "at_horizon_fraction"]
STAT_COLUMNS = ["n", "mean", "std"] + [f"p{p}" for p in PERCENTILES] + STREAM_COLUMNS + END_COLUMNS
# a grain's end (`ends`): it left the chute, came to rest on it, or was still on it at the
# horizon; None where its row does not say which of the last two
EXITED, AT_REST, AT_HORIZON = "exited", "at_rest", "at_horizon"
END_AT_REST = 3  # tribo.EndReason at_rest (populations/feed.py)
CLASSES = 4  # equal-width classes over the population's range, unless edges are given


def checked_edges(edges, what: str = "class edges") -> np.ndarray:
    """Class edges given (`what` names them in the message): at least two finite numbers,
    increasing; ValueError, one line, otherwise. Checked before any run (a job's prepare,
    the commands' option), not once every grain has run."""
    try:
        values = np.asarray([float(e) for e in edges])
    except (TypeError, ValueError):
        raise ValueError(f"{what} {edges!r}: numbers".strip()) from None
    if len(values) < 2 or not np.all(np.isfinite(values)) or not np.all(np.diff(values) > 0):
        shown = ",".join(f"{v:g}" for v in values)
        raise ValueError(f"{what} {shown}: at least two finite numbers, increasing".strip())
    return values


def check_class_edges(shape_edges, size_edges) -> None:
    """A job's shape and size class edges, where given, checked (checked_edges)."""
    for what, edges in (("shape class edges", shape_edges), ("size class edges", size_edges)):
        if edges is not None:
            checked_edges(edges, what)


def class_edges(values: pd.Series, edges=None) -> np.ndarray:
    """The class edges: those given, or CLASSES equal-width classes over the values' range."""
    if edges is not None:
        return checked_edges(edges)
    lo, hi = float(values.min()), float(values.max())
    return np.linspace(lo, hi, CLASSES + 1) if hi > lo else np.array([lo, lo + max(abs(lo), 1.0) * 1e-9])


def statistics(values: pd.Series, mass: pd.Series | None = None,
               exited: pd.Series | None = None, ends: pd.Series | None = None) -> dict:
    """n, mean, sample standard deviation and percentiles of the values (NaN where
    undefined), then the stream's (stream_statistics, with the grains' masses and whether
    they left) and the grains that did not leave, by why (end_statistics, with `ends`)."""
    v = values.to_numpy(dtype=float)
    n = len(v)
    stats = {"n": n, "mean": v.mean() if n else np.nan, "std": v.std(ddof=1) if n > 1 else np.nan}
    for p in PERCENTILES:
        stats[f"p{p}"] = np.percentile(v, p) if n else np.nan
    stats.update(stream_statistics(values, mass, exited))
    stats.update(end_statistics(ends, mass))
    return stats


def ends_of(results: pd.DataFrame) -> pd.Series | None:
    """Each grain's end: EXITED, AT_REST or AT_HORIZON, from its row's `exited` and
    `end_reason` (or `at_rest`); None where the rows lack `exited`. A row that does not say
    why a grain that stayed stopped (an FMU without the outputs) gets None."""
    if "exited" not in results.columns:
        return None
    exited = results["exited"].astype(float) != 0
    if "end_reason" in results.columns:
        rest = results["end_reason"].astype(float) == END_AT_REST
        known = results["end_reason"].notna()
    elif "at_rest" in results.columns:
        rest = results["at_rest"].astype(float) != 0
        known = results["at_rest"].notna()
    else:
        rest = known = pd.Series(False, index=results.index)
    out = np.where(exited, EXITED, np.where(~known, None, np.where(rest, AT_REST, AT_HORIZON)))
    return pd.Series(out, index=results.index, dtype=object)


def end_statistics(ends: pd.Series | None, mass: pd.Series | None) -> dict:
    """How many grains left the chute, came to rest on it and were still on it at the
    horizon, and the mass fraction of the last two; NaN where the rows do not say (the
    counts) or lack the masses (the fractions)."""
    out = dict.fromkeys(END_COLUMNS, np.nan)
    if ends is None:
        return out
    e = ends.to_numpy(dtype=object)
    out["n_exited"] = int((e == EXITED).sum())
    if any(v is None for v in e):
        return out
    out["n_at_rest"] = int((e == AT_REST).sum())
    out["n_at_horizon"] = int((e == AT_HORIZON).sum())
    if mass is not None:
        m = mass.to_numpy(dtype=float)
        total = m.sum()
        if total > 0:
            out["at_rest_fraction"] = float(m[e == AT_REST].sum() / total)
            out["at_horizon_fraction"] = float(m[e == AT_HORIZON].sum() / total)
    return out


def grain_mass(results: pd.DataFrame) -> pd.Series | None:
    """Each grain's mass (kg) from its row: the spheroid's (4/3) pi rho a b^2 = (pi/6) rho
    size^3 epsilon^2 (docs/model.md section 8c), or the cylinder's rho pi a^2 epsilon l
    where the row sets grain_geometry 0; None where the rows lack the density or the size."""
    if not {"density", "size", "epsilon"} <= set(results.columns):
        return None
    rho, size, eps = (results[c].astype(float) for c in ("density", "size", "epsilon"))
    spheroid = math.pi / 6.0 * rho * size ** 3 * eps ** 2
    if "grain_geometry" not in results.columns:
        return spheroid
    depth = results["cylinder_length"].astype(float) if "cylinder_length" in results.columns \
        else np.nan
    cylinder = rho * math.pi * (size / 2.0) ** 2 * eps * depth
    return spheroid.where(results["grain_geometry"].astype(float) != 0, cylinder)


def stream_statistics(q_per_m: pd.Series, mass: pd.Series | None,
                      exited: pd.Series | None) -> dict:
    """The stream that leaves the chute (a Faraday cup at its end): its mass-weighted mean
    q/m (the grains' charge over their mass, C/kg) and the mass-weighted standard deviation
    of q/m about it, over the grains that left; the mass fraction that stayed. NaN where
    the rows do not say the masses or whether the grains left, or no grain left."""
    if mass is None or exited is None:
        return dict.fromkeys(STREAM_COLUMNS, np.nan)
    m = mass.to_numpy(dtype=float)
    left = exited.to_numpy(dtype=float) != 0
    total = m.sum()
    stayed = float(m[~left].sum() / total) if total > 0 else np.nan
    m_out, q = m[left], q_per_m.to_numpy(dtype=float)[left]
    if not m_out.sum() > 0:
        return {"stream_mean": np.nan, "stream_std": np.nan, "stayed": stayed}
    mean = float((m_out * q).sum() / m_out.sum())
    std = float(math.sqrt((m_out * (q - mean) ** 2).sum() / m_out.sum()))
    return {"stream_mean": mean, "stream_std": std, "stayed": stayed}


def classes_of(values: pd.Series, edges: np.ndarray) -> pd.Series:
    """Each value's class as a label "[lo, hi]" (the first class closed on both sides)."""
    return pd.cut(values, edges, include_lowest=True)


def summarize_population(results: pd.DataFrame, models, shape_edges=None,
                         size_edges=None) -> pd.DataFrame:
    """One row per (charge model of `models`, grouping, class): grouping "all", "shape"
    (classes of epsilon) or "size" (classes of the long diameter, m), with the class's
    edges and the statistics of q/m (C/kg) over its particles (`statistics`: the stream's
    mass-weighted ones too, where the rows give the masses and `exited`, and the grains that
    stayed on the chute by why, where the rows say it)."""
    mass = grain_mass(results)
    exited = results["exited"] if "exited" in results.columns else None
    ends = ends_of(results)
    rows = []
    groupings = [("all", None, None),
                 ("shape", "epsilon", class_edges(results["epsilon"], shape_edges)),
                 ("size", "size", class_edges(results["size"], size_edges))]
    for model in models:
        qm = results[f"charge_to_mass_{model}"]
        for grouping, column, edges in groupings:
            if column is None:
                rows.append({"grouping": grouping, "class": "all", "low": np.nan, "high": np.nan,
                             "model": model, **statistics(qm, mass, exited, ends)})
                continue
            labels = classes_of(results[column], edges)
            for i, interval in enumerate(labels.cat.categories):
                lo, hi = edges[i], edges[i + 1]
                inside = labels == interval
                rows.append({"grouping": grouping, "class": f"{column} {lo:.3g} to {hi:.3g}",
                             "low": lo, "high": hi, "model": model,
                             **statistics(qm[inside], None if mass is None else mass[inside],
                                          None if exited is None else exited[inside],
                                          None if ends is None else ends[inside])})
    return pd.DataFrame(rows, columns=["grouping", "class", "low", "high", "model"] + STAT_COLUMNS)


def edges_of(summary: pd.DataFrame, grouping: str) -> np.ndarray:
    """The class edges of a grouping ("shape" or "size") as the summary holds them."""
    rows = summary[(summary["grouping"] == grouping) & (summary["model"] == summary["model"].iloc[0])]
    return np.append(rows["low"].to_numpy(dtype=float), float(rows["high"].iloc[-1]))


def ends_text(row, horizon: float | None = None) -> str:
    """How the grains of a summary's row ended, in words: how many left the chute, came to
    rest on it and were still on it at the horizon (s), with the share of the mass of the
    last two; what the rows do not say is left out."""
    def share(column):
        value = row[column]
        return f" ({100 * value:.3g} % of the mass)" if np.isfinite(value) else ""

    n_exited = row["n_exited"]
    if not np.isfinite(n_exited):
        return f"{int(row['n'])} grains (the rows do not say which left the chute)"
    text = f"{int(row['n'])} grains: {int(n_exited)} left the chute"
    if not np.isfinite(row["n_at_rest"]):
        stayed = int(row["n"]) - int(n_exited)
        return text + f", {stayed} did not{share('stayed')}"
    at = f" of {horizon:g} s" if horizon is not None else ""
    return (text + f", {int(row['n_at_rest'])} at rest on it{share('at_rest_fraction')}, "
            f"{int(row['n_at_horizon'])} still on it at the horizon{at}"
            f"{share('at_horizon_fraction')}")
