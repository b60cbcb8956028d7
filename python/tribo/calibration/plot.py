"""The figure of a calibration: each kind of point's measured value against the model's
(log-log, the magnitudes, drawn with the pair's polarity), the line model = measured and a
factor of 2 either side; and, where t0 was fitted with the static model, the fit's RMS
error against t0 (the profile: where the data stop telling t0 apart)."""

import math

import numpy as np

from matplotlib.ticker import NullFormatter

from ..plotting import legend, plt, save

UNITS = {"impact": ("charge picked up, |Δq| (pC)", 1e12),
         "chute": ("stream q/m, |q/m| (nC/g = µC/kg)", 1e6)}


def calibration_figure(points, profile, fit, particle: str, wall: str, charge_model: str):
    kinds = [k for k in ("impact", "chute") if (points["kind"] == k).any()]
    panels = len(kinds) + (profile is not None)
    fig, axes = plt.subplots(1, panels, figsize=(5.2 * panels, 4.6), squeeze=False)
    axes = list(axes[0])
    sign = float(np.sign(points["measured"].iloc[0]))
    for ax, kind in zip(axes, kinds):
        rows = points[points["kind"] == kind]
        label, scale = UNITS[kind]
        x = np.abs(rows["measured"].to_numpy(dtype=float)) * scale
        y = np.abs(rows["model"].to_numpy(dtype=float)) * scale
        std_column = "charge_std" if kind == "impact" else "q_per_m_std"
        err = rows[std_column].to_numpy(dtype=float) * scale if std_column in rows else None
        has_err = err is not None and np.all(np.isfinite(err))
        ax.errorbar(x, y, xerr=err if has_err else None, fmt="o", ms=5, capsize=2,
                    label=f"{len(rows)} {'impacts' if kind == 'impact' else 'chute runs'}"
                          + (" (±1 std measured)" if has_err else ""))
        both = np.concatenate([x, y])
        both = both[both > 0]
        # whole decades, at least two: labelled major ticks on a narrow range too
        lo = 10.0 ** math.floor(math.log10(both.min() / 1.5))
        hi = 10.0 ** math.ceil(math.log10(both.max() * 1.5))
        line = np.array([lo, hi])
        ax.plot(line, line, "k-", lw=1, label="model = measured")
        ax.plot(line, 2 * line, "k:", lw=1, label="factor 2")
        ax.plot(line, line / 2, "k:", lw=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(lo, hi)
        ax.set_ylim(lo, hi)
        for axis in (ax.xaxis, ax.yaxis):
            axis.set_minor_formatter(NullFormatter())
        polarity = "" if sign > 0 else " (negative)"
        ax.set_xlabel(f"measured {label}{polarity}")
        ax.set_ylabel(f"model {label}{polarity}")
        ax.set_title(f"{'single impacts' if kind == 'impact' else 'chute runs'}", fontsize=10)
        legend(ax, loc="upper left")
    if profile is not None:
        ax = axes[-1]
        positive = profile[profile["charging_time"] > 0]
        ax.plot(positive["charging_time"], positive["rms_log10"], "o-", ms=4,
                label="sigma0 fitted at each t0")
        zero = profile[profile["charging_time"] == 0]
        if len(zero):
            ax.axhline(float(zero["rms_log10"].iloc[0]), color="C2", ls="--",
                       label="t0 = 0 (complete transfer)")
        t0 = fit.values.get("charging_time", math.nan)
        if t0 and math.isfinite(t0):
            ax.axvline(t0, color="C3", ls=":", label=f"fitted t0 = {t0:.2g} s")
        ax.set_xscale("log")
        ax.set_xlabel("charging time t0 (s)")
        ax.set_ylabel("RMS of log10(model / measured)")
        ax.set_title("the fit against t0", fontsize=10)
        legend(ax, loc="upper left")
    fig.suptitle(f"{particle} on {wall}, {charge_model} model: "
                 + "; ".join(_said(fit, n) for n in fit.values)
                 + f"; RMS error {fit.rms_log10:.3f} decades", fontsize=11)
    fig.tight_layout()
    return fig


SYMBOLS = {"sigma0": ("σ0", "C/m²"), "charging_time": ("t0", "s"), "eta": ("η", "")}


def _said(fit, name: str) -> str:
    """A parameter in the title: its value ± its standard deviation, or its status."""
    symbol, unit = SYMBOLS.get(name, (name, ""))
    value, std, status = fit.values[name], fit.stds.get(name, math.nan), fit.status[name]
    text = f"{symbol} = {value:.3g}" + (f" ± {std:.2g}" if status == "fitted" and std == std else "")
    text += f" {unit}" if unit else ""
    if status == "lower bound":  # data at the gas's limit (docs/model.md section 8e)
        return f"|{symbol}| ≥ {abs(value):.3g}" + (f" {unit}" if unit else "")
    return text if status == "fitted" else f"{text} ({status})"


def write_calibration_figure(points, profile, fit, particle, wall, charge_model, path: str) -> str:
    return save(calibration_figure(points, profile, fit, particle, wall, charge_model), path)
