"""What a run's time series is summarised into: one row of numbers.

Definitions (used in the tables, the figures and the docs):

* bounce amplitude: the upper envelope of the centre height Y, taken as the maximum of
  the recorded Y over a centred sliding window of ENVELOPE_WIDTH time units
  (`upper_envelope`). The paper plots the upper envelope of Y; the window is wide enough
  to span a bounce or a turn of the particle (tens of time units) and short against the
  run. Y is recorded every `record_interval` (1 time unit), which resolves a ballistic
  apex to ~1e-4 (Gamma cos(beta) (1/2)^2 / 2).
* charges: the mean charge Q_<model> of each charge model the FMU outputs one for
  (Q_static and Q_sliding: fmu/charge_models.py's `mean_charges`) at REPORT_FRACTIONS of
  the horizon (1000, 2000, ..., 5000 for the paper's tau = 5000), in columns named by the
  fraction, not the time (Q_static_20pct, ..., Q_static_end), so that runs of different
  horizons share them.
* motion classes: the FMU's fractions of time in each class over the whole run, and the
  same fractions after the warm-up (the FMU classifies over a ~20-unit exponential
  window, so the first WARMUP units read as "bouncing" while that window fills up). The
  after-warm-up fractions are exact differences of the FMU's cumulative class times:
  (f(T) T - f(tw) tw) / (T - tw), with tw the first recorded time >= WARMUP.
* delta_y_max: the largest recorded indentation. The contact law assumes it small
  (the FMU counts excursions beyond 0.1 min(epsilon, rho_c) in assumption_warnings).
* turned over: the orientation has at some recorded time moved by at least
  TURNED_OVER revolutions from its start (|phi - phi0| >= pi: onto the other side).
* how the run ended (END_OUTPUTS at its last recorded time, NaN where the FMU lacks them):
  `exited` (it left the chute), `end_reason` (tribo.EndReason: 0 still running at the
  horizon, 1 chute_exit, 2 first_liftoff, 3 at_rest), `at_rest` and `rest_time` (when it
  came to rest, docs/model.md section 3c). A run that ended before its horizon is recorded
  up to there: its charges "at" a later fraction of the horizon are those it ended with
  (held, as the FMU holds them).
"""

from __future__ import annotations  # the DataFrames summarised are the caller's

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:  # not imported here: a population's worker process needs MOTION_CLASSES only
    import pandas as pd

ENVELOPE_WIDTH = 50.0
WARMUP = 60.0  # three classification windows of the FMU (TRIBO_MOTION_WINDOW = 20)
TURNED_OVER = 0.5
REPORT_FRACTIONS = (0.2, 0.4, 0.6, 0.8, 1.0)
MOTION_CLASSES = ("flight", "rocking", "rolling", "tumbling", "bouncing")  # motion_class 0..4
END_OUTPUTS = ("exited", "end_reason", "at_rest", "rest_time")


def report_times(t_end: float) -> list[float]:
    """The times at which the charges are reported: 1000, ..., 5000 for t_end = 5000."""
    return [round(t_end * f, 9) for f in REPORT_FRACTIONS]


def charge_column(model: str, fraction: float) -> str:
    """The column of a charge model's Q at a fraction of the horizon: Q_static_20pct, ...,
    Q_static_end."""
    return f"Q_{model}_end" if fraction == 1.0 else f"Q_{model}_{round(100 * fraction)}pct"


def charge_columns(model: str) -> list[str]:
    return [charge_column(model, f) for f in REPORT_FRACTIONS]


def upper_envelope(y: np.ndarray, samples_per_window: int) -> np.ndarray:
    """Maximum of y over a centred window of `samples_per_window` samples (odd: the
    sample itself and (n-1)/2 on each side), shortened at the ends."""
    half = max(0, samples_per_window // 2)
    padded = np.concatenate([np.full(half, -np.inf), np.asarray(y, float), np.full(half, -np.inf)])
    return np.lib.stride_tricks.sliding_window_view(padded, 2 * half + 1).max(axis=1)


def bounce_envelope(series: pd.DataFrame, width: float = ENVELOPE_WIDTH) -> np.ndarray:
    """The bounce amplitude at every recorded time (see the module's definition)."""
    tau = series["time"].to_numpy()
    interval = (tau[-1] - tau[0]) / max(1, len(tau) - 1)
    return upper_envelope(series["Y"].to_numpy(), int(round(width / interval)) | 1)


def fractions_after(series: pd.DataFrame, t_from: float) -> dict[str, float]:
    """Fraction of the time after t_from spent in each motion class (NaN if the run is
    shorter)."""
    tau = series["time"].to_numpy()
    i = int(np.searchsorted(tau, t_from - 1e-9))
    if i >= len(tau) - 1:
        return {m: math.nan for m in MOTION_CLASSES}
    t0, t1 = tau[i], tau[-1]
    out = {}
    for m in MOTION_CLASSES:
        f = series[f"fraction_{m}"].to_numpy()
        # a difference of two cumulative times: clip the rounding below 0 (e.g. -1e-17 for
        # a class seen only during the warm-up)
        out[m] = max(0.0, (f[-1] * t1 - f[i] * t0) / (t1 - t0))
    return out


def summary_columns(models) -> list[str]:
    """The names of `summarize`'s row for the charge models `models`, in its order (a
    results file's header needs them before the first run has finished); the same for
    every horizon."""
    charges = [c for model in models for c in charge_columns(model)]
    return (charges + ["contact_fraction", "turns", "turns_max", "turned_over", "motion_class_end"]
            + [f"fraction_{m}" for m in MOTION_CLASSES]
            + [f"fraction_{m}_after_warmup" for m in MOTION_CLASSES]
            + ["assumption_warnings", "delta_y_max", "Y_max", "bounce_amplitude_end",
               "bounce_amplitude_mean"] + list(END_OUTPUTS))


def summarize(series: pd.DataFrame, t_end: float, models) -> dict:
    """The summary row of a run (column name -> number), with the charges Q_<model> of
    `models`."""
    tau = series["time"].to_numpy()
    last = series.iloc[-1]
    row = {}
    for model in models:
        q = series[f"Q_{model}"].to_numpy()
        for f, t in zip(REPORT_FRACTIONS, report_times(t_end)):
            row[charge_column(model, f)] = float(np.interp(t, tau, q))
    turns_max = float(series["turns"].max())
    row.update(
        contact_fraction=float(last["contact_fraction"]),
        turns=float(last["turns"]),
        turns_max=turns_max,
        turned_over=int(turns_max >= TURNED_OVER),
        motion_class_end=int(last["motion_class"]),
    )
    for m in MOTION_CLASSES:
        row[f"fraction_{m}"] = float(last[f"fraction_{m}"])
    for m, f in fractions_after(series, WARMUP).items():
        row[f"fraction_{m}_after_warmup"] = float(f)
    envelope = bounce_envelope(series)
    row.update(
        assumption_warnings=int(last["assumption_warnings"]),
        delta_y_max=float(series["delta_y"].max()),  # at the recorded times
        Y_max=float(series["Y"].max()),
        bounce_amplitude_end=float(envelope[-1]),
        bounce_amplitude_mean=float(envelope[tau >= WARMUP].mean()) if tau[-1] >= WARMUP else math.nan,
    )
    for name in END_OUTPUTS:
        value = float(last[name]) if name in series.columns else math.nan
        row[name] = value if name == "rest_time" or not math.isfinite(value) else int(value)
    return row


def ends_text(results: pd.DataFrame) -> str:
    """How a sweep's runs ended, in words (how many ran to the horizon, came to rest on the
    chute, left it, ended at a first lift-off); "" where the rows do not say."""
    if "end_reason" not in results.columns or results["end_reason"].isna().any():
        return ""
    reason = results["end_reason"].astype(int)
    words = ((0, "ran to the horizon"), (3, "came to rest on the chute"), (1, "left the chute"),
             (2, "ended at their first lift-off"))
    return "of the runs, " + ", ".join(f"{int((reason == code).sum())} {text}"
                                       for code, text in words if code < 2 or (reason == code).any())
