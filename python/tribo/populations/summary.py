"""What a process engineer reads off a population: the charge-to-mass distribution of each
charge model (count, mean, standard deviation, percentiles) over all particles, per shape
class (ranges of epsilon) and per size class (ranges of the long diameter).

The summary is computed once, from the particles' rows, and holds the class edges (`low`,
`high`) with the statistics: the figure (plot.py) draws it, it does not compute them again."""

import numpy as np
import pandas as pd

PERCENTILES = (5, 25, 50, 75, 95)
STAT_COLUMNS = ["n", "mean", "std"] + [f"p{p}" for p in PERCENTILES]
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


def statistics(values: pd.Series) -> dict:
    """n, mean, sample standard deviation and percentiles of the values (NaN where undefined)."""
    v = values.to_numpy(dtype=float)
    n = len(v)
    stats = {"n": n, "mean": v.mean() if n else np.nan, "std": v.std(ddof=1) if n > 1 else np.nan}
    for p in PERCENTILES:
        stats[f"p{p}"] = np.percentile(v, p) if n else np.nan
    return stats


def classes_of(values: pd.Series, edges: np.ndarray) -> pd.Series:
    """Each value's class as a label "[lo, hi]" (the first class closed on both sides)."""
    return pd.cut(values, edges, include_lowest=True)


def summarize_population(results: pd.DataFrame, models, shape_edges=None,
                         size_edges=None) -> pd.DataFrame:
    """One row per (charge model of `models`, grouping, class): grouping "all", "shape"
    (classes of epsilon) or "size" (classes of the long diameter, m), with the class's
    edges and the statistics of q/m (C/kg) over its particles."""
    rows = []
    groupings = [("all", None, None),
                 ("shape", "epsilon", class_edges(results["epsilon"], shape_edges)),
                 ("size", "size", class_edges(results["size"], size_edges))]
    for model in models:
        qm = results[f"charge_to_mass_{model}"]
        for grouping, column, edges in groupings:
            if column is None:
                rows.append({"grouping": grouping, "class": "all", "low": np.nan, "high": np.nan,
                             "model": model, **statistics(qm)})
                continue
            labels = classes_of(results[column], edges)
            for i, interval in enumerate(labels.cat.categories):
                lo, hi = edges[i], edges[i + 1]
                rows.append({"grouping": grouping, "class": f"{column} {lo:.3g} to {hi:.3g}",
                             "low": lo, "high": hi, "model": model,
                             **statistics(qm[labels == interval])})
    return pd.DataFrame(rows, columns=["grouping", "class", "low", "high", "model"] + STAT_COLUMNS)


def edges_of(summary: pd.DataFrame, grouping: str) -> np.ndarray:
    """The class edges of a grouping ("shape" or "size") as the summary holds them."""
    rows = summary[(summary["grouping"] == grouping) & (summary["model"] == summary["model"].iloc[0])]
    return np.append(rows["low"].to_numpy(dtype=float), float(rows["high"].iloc[-1]))
