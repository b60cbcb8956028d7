"""The measured data a calibration takes: CSV files of a header row and a row per point.

Impacts (`IMPACT_COLUMNS`): a grain of `size` (the long diameter 2a, m) and roundness
`epsilon` meets a fresh level wall of the pair's at `speed` (m/s) and `angle_deg` (degrees
to the wall, 90 head-on), long axis at `phi0_deg` to it (default 0), carrying
`initial_charge` (C, default 0) spread over its surface; `charge` is what it picked up
(Delta q, C; with `impacts` n > 1, over n impacts on fresh spots, the charge spread over
the grain between them: observables' text), `charge_std` its standard deviation (C).

Chute runs (`CHUTE_COLUMNS`): a feed down a chute of `chute_length` (m) tilted `tilt_deg`;
`q_per_m` the mass-weighted mean q/m of the grains that left it (C/kg: a Faraday cup at its
end), `q_per_m_std` its standard deviation (C/kg, of the measurement, not the grains'
spread). The feed: `grains` (how many the model draws, default 50) with `seed` (default
0), and the feed variables of tribo.population (epsilon, size, phi0_deg, omega0,
drop_height, drop_speed, drop_angle_deg), each a number or a distribution text
("uniform:0.3:1", "lognormal:1e-3:0.3"; default the population's feed), `t_end` (s,
default 5) the horizon.

Every point of a file is of one particle on one wall (the calibration's). A file that
cannot be used is refused in one line naming it and, where it is one, the row and column
(`DataError`): no rows, a missing or unknown column, a value that is not a finite number or
lies outside its range (negative where only positive values are measured), a zero charge,
charges of both signs (a pair charges with one polarity).
"""

import csv
import hashlib
import io
import math
import os
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..fmu.names import format_number
from ..input_files import read_input, shown
from ..populations.distributions import parse
from .columns import CHUTE_COLUMNS, FEED_COLUMNS, IMPACT_COLUMNS, WHOLE, columns_text


class DataError(ValueError):
    """Measured data that cannot be calibrated against (one line naming the file, the row
    and the column)."""


@dataclass(frozen=True)
class Data:
    """A data file as read: its rows (`frame`, the columns completed with their defaults),
    where it came from (`source`: the path, or "the <kind> given") and its digest."""

    kind: str  # "impacts" or "chutes"
    frame: pd.DataFrame
    source: str
    sha256: str


def read(kind: str, data) -> Data:
    """The impacts (kind "impacts") or chute runs ("chutes") of a CSV path or a DataFrame,
    checked (the module's text)."""
    if kind not in ("impacts", "chutes"):
        raise DataError(f"kind {kind!r}: 'impacts' or 'chutes'")
    if isinstance(data, pd.DataFrame):  # a missing value (NaN, None) is an empty cell
        frame, source = data.astype(object).where(data.notna(), ""), f"the {kind} given"
    else:
        source = os.fspath(data)
        text = read_input(source, DataError, f"the {kind} file")
        if not text:
            raise DataError(f"{source}: empty file (expected a header row and a row per point: "
                            f"{columns_text(kind)})")
        frame = _table(text, source)
    frame.columns = [str(c).strip() for c in frame.columns]
    frame = checked(kind, frame, source)
    text = frame.to_csv(index=False, float_format="%.17g").encode()
    return Data(kind, frame, source, hashlib.sha256(text).hexdigest())


def _table(text: bytes, source: str) -> pd.DataFrame:
    """A CSV's cells as text, every row as many as the header's (pandas would take a row of
    more as one whose first cells are an index, and blame the columns its values move to)."""
    try:
        rows = list(csv.reader(io.StringIO(text.decode("utf-8-sig")), skipinitialspace=True))
    except (UnicodeDecodeError, csv.Error) as e:
        raise DataError(f"{source}: cannot read it as CSV ({shown(str(e).splitlines()[0])})") from None
    rows = [r for r in rows if r]  # blank lines
    if not rows:
        raise DataError(f"{source}: no header row")
    header = rows[0]
    for i, row in enumerate(rows[1:]):
        if len(row) != len(header):
            raise DataError(f"{source}: row {i + 2} has {len(row)} fields, the header "
                            f"{len(header)} ({shown(','.join(header))})")
    return pd.DataFrame(rows[1:], columns=header, dtype=str)


def checked(kind: str, frame: pd.DataFrame, source: str) -> pd.DataFrame:
    numeric = IMPACT_COLUMNS if kind == "impacts" else CHUTE_COLUMNS
    feed = FEED_COLUMNS if kind == "chutes" else {}
    known = list(numeric) + list(feed)
    unknown = [c for c in frame.columns if c not in known]
    if unknown:
        raise DataError(f"{source}: unknown column {shown(repr(unknown[0]))} (the {kind}' columns: "
                        f"{columns_text(kind)})")
    duplicated = [c for c in frame.columns if list(frame.columns).count(c) > 1]
    if duplicated:
        raise DataError(f"{source}: column {shown(repr(duplicated[0]))} given twice")
    missing = [n for n, c in numeric.items() if c[1] and n not in frame.columns]
    if missing:
        raise DataError(f"{source}: missing column {missing[0]!r} (the {kind}' columns: "
                        f"{columns_text(kind)})")
    if len(frame) == 0:
        raise DataError(f"{source}: no rows (a row per point: {columns_text(kind)})")
    out = pd.DataFrame(index=range(len(frame)))
    for name, (unit, required, low, high, open_low, default) in numeric.items():
        if name not in frame.columns:
            out[name] = np.nan if default is None else default
            continue
        values = []
        for i, text in enumerate(frame[name].tolist()):
            values.append(_number(text, name, unit, low, high, open_low, source, i,
                                  optional=not required, default=default))
        out[name] = values
    for name in WHOLE:
        if name in out and not all(float(v).is_integer() for v in out[name]):
            i = next(i for i, v in enumerate(out[name]) if not float(v).is_integer())
            raise DataError(f"{source}: row {i + 2}, {name} = {format_number(float(out[name][i]))}: "
                            f"a whole number")
    for name, unit in feed.items():
        if name in frame.columns:
            texts = []
            for i, text in enumerate(frame[name].tolist()):
                text = str(text).strip()
                if text:
                    try:
                        parse(name, text)
                    except ValueError as e:
                        raise DataError(f"{source}: row {i + 2}, {name}: {shown(e, 200)}") from None
                texts.append(text)
            out[name] = texts
    value = "charge" if kind == "impacts" else "q_per_m"
    zero = [i for i, v in enumerate(out[value]) if v == 0]
    if zero:
        raise DataError(f"{source}: row {zero[0] + 2}, {value} = 0: a calibration needs charges "
                        f"that are not 0")
    signs = set(np.sign(out[value]))
    if len(signs) > 1:
        i = next(i for i, v in enumerate(out[value]) if np.sign(v) != np.sign(out[value][0]))
        raise DataError(f"{source}: {value} has both signs (row 2: {out[value][0]:g}, row {i + 2}: "
                        f"{out[value][i]:g}): one pair charges with one polarity; calibrate "
                        f"each polarity's data apart, or check the signs")
    return out


def _number(text, name, unit, low, high, open_low, source, i, *, optional, default):
    where = f"{source}: row {i + 2}, {name}"
    text = str(text).strip()
    if text == "" and optional:
        return np.nan if default is None else default
    try:
        value = float(text)
    except ValueError:
        raise DataError(f"{where} = {shown(repr(text))}: not a number ({unit})") from None
    if not math.isfinite(value):
        raise DataError(f"{where} = {text}: not a finite number ({unit})")
    if value < low or (open_low and value == low) or value > high:
        if value < 0 and low >= 0:
            raise DataError(f"{where} = {text}: negative ({unit}; from {low:g}"
                            f"{' exclusive' if open_low else ''} to {high:g})")
        bound = f"{'(' if open_low else '['}{low:g}, {high:g}]"
        raise DataError(f"{where} = {text}: outside {bound} ({unit})")
    return value


def combined_sign(datasets) -> float:
    """The one sign of every dataset's charges (DataError for two)."""
    signs = {}
    for d in datasets:
        value = "charge" if d.kind == "impacts" else "q_per_m"
        signs.setdefault(float(np.sign(d.frame[value].iloc[0])), d)
    if len(signs) > 1:
        a, b = signs.values()
        raise DataError(f"the charges of {a.source} and {b.source} have opposite signs: one pair "
                        f"charges with one polarity")
    return next(iter(signs))
