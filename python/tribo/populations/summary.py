"""What a process engineer reads off a population: the charge-to-mass distribution of each
charge model (count, mean, standard deviation, percentiles) over all particles, per shape
class (ranges of epsilon) and per size class (ranges of the long diameter), and what a
Faraday cup at the chute's end reads (docs/model.md section 8d): the stream of the grains
that leave the chute, its mass-weighted mean q/m (their charge over their mass) and the
mass-weighted spread of q/m about it, and the mass fraction that stays on the chute.

The summary is computed once, from the particles' rows, and holds the class edges (`low`,
`high`) with the statistics: the figure (plot.py) draws it, it does not compute them again."""

import math

import numpy as np
import pandas as pd

PERCENTILES = (5, 25, 50, 75, 95)
# the stream's: mass-weighted mean and standard deviation of q/m over the grains that left
# the chute (C/kg), the mass fraction that did not leave
STREAM_COLUMNS = ["stream_mean", "stream_std", "stayed"]
STAT_COLUMNS = ["n", "mean", "std"] + [f"p{p}" for p in PERCENTILES] + STREAM_COLUMNS
CLASSES = 4  # equal-width classes over the population's range, unless edges are given


def class_edges(values: pd.Series, edges=None) -> np.ndarray:
    """The class edges: those given, or CLASSES equal-width classes over the values' range."""
    if edges is not None:
        edges = np.asarray([float(e) for e in edges])
        if len(edges) < 2 or not np.all(np.diff(edges) > 0) or not np.all(np.isfinite(edges)):
            raise ValueError(f"class edges {list(edges)}: at least two finite numbers, increasing")
        return edges
    lo, hi = float(values.min()), float(values.max())
    return np.linspace(lo, hi, CLASSES + 1) if hi > lo else np.array([lo, lo + max(abs(lo), 1.0) * 1e-9])


def statistics(values: pd.Series, mass: pd.Series | None = None,
               exited: pd.Series | None = None) -> dict:
    """n, mean, sample standard deviation and percentiles of the values (NaN where
    undefined), then the stream's (stream_statistics, with the grains' masses and whether
    they left)."""
    v = values.to_numpy(dtype=float)
    n = len(v)
    stats = {"n": n, "mean": v.mean() if n else np.nan, "std": v.std(ddof=1) if n > 1 else np.nan}
    for p in PERCENTILES:
        stats[f"p{p}"] = np.percentile(v, p) if n else np.nan
    stats.update(stream_statistics(values, mass, exited))
    return stats


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
    mass-weighted ones too, where the rows give the masses and `exited`)."""
    mass = grain_mass(results)
    exited = results["exited"] if "exited" in results.columns else None
    rows = []
    groupings = [("all", None, None),
                 ("shape", "epsilon", class_edges(results["epsilon"], shape_edges)),
                 ("size", "size", class_edges(results["size"], size_edges))]
    for model in models:
        qm = results[f"charge_to_mass_{model}"]
        for grouping, column, edges in groupings:
            if column is None:
                rows.append({"grouping": grouping, "class": "all", "low": np.nan, "high": np.nan,
                             "model": model, **statistics(qm, mass, exited)})
                continue
            labels = classes_of(results[column], edges)
            for i, interval in enumerate(labels.cat.categories):
                lo, hi = edges[i], edges[i + 1]
                inside = labels == interval
                rows.append({"grouping": grouping, "class": f"{column} {lo:.3g} to {hi:.3g}",
                             "low": lo, "high": hi, "model": model,
                             **statistics(qm[inside], None if mass is None else mass[inside],
                                          None if exited is None else exited[inside])})
    return pd.DataFrame(rows, columns=["grouping", "class", "low", "high", "model"] + STAT_COLUMNS)


def edges_of(summary: pd.DataFrame, grouping: str) -> np.ndarray:
    """The class edges of a grouping ("shape" or "size") as the summary holds them."""
    rows = summary[(summary["grouping"] == grouping) & (summary["model"] == summary["model"].iloc[0])]
    return np.append(rows["low"].to_numpy(dtype=float), float(rows["high"].iloc[-1]))
