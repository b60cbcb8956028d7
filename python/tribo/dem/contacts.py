"""The grain-wall impacts and the exits, read from a LIGGGHTS run's outputs (script.py).

**Sampling.** contacts.dump holds, every `sample_every` steps (a third of the fastest
impact's Hertz contact time, script.py), each grain whose gap to the plate is below `near`
(twice what the fastest grain covers in a sample) and whose normal speed exceeds
`slowest`; the wall's normal force on it says whether it touches. So every impact has at
least one sample in flight just before it and several in contact: none is missed, and
one that lasts less than a sample interval would be one the time step does not resolve.

**An impact** is a grain's first sample in contact after a sample in flight (or after
none: a grain that entered touching). Its onset is the free flight from the sample
before carried to the contact (exact: gravity alone acts in flight): the normal speed
`v_n = sqrt(v_z^2 + 2 g_n (z - r))`, and the tangential velocity advanced by g_t over the
time it takes. Without a sample in flight (a grain written first in contact) the onset is
the first contact sample's velocity (`from_flight` = 0 says so). Its duration runs to its
last sample in contact, to a sample interval; a contact whose grain stops being written
while it still touches, leaving it slower than SETTLED (it rests or rolls on the plate:
normal speed below `slowest`) is `sustained`, its duration then a lower bound.

Per impact (`impacts`): grain (0-based, the feed's order), time (s, the onset), normal
and tangential speed (m/s), angle (degrees from the plate's surface, 90 head-on),
duration (s), sustained, from_flight.
"""

import io
import os
import re

import numpy as np
import pandas as pd

from .script import CONTACT_COLUMNS, EXIT_COLUMNS

SETTLED = 1e-2  # m/s: a contact left slower than this along the normal is sustained
IMPACT_COLUMNS = ["grain", "time", "normal_speed", "tangential_speed", "angle_deg",
                  "duration", "sustained", "from_flight"]


class OutputError(ValueError):
    """A LIGGGHTS output that cannot be read (the message names the file)."""


def impacts(path: str, dt: float, sample_every: int, gravity: tuple, n: int,
            wall=None) -> pd.DataFrame:
    """The impacts (the module's text) of contacts.dump, a run of time step dt (s) sampled
    every sample_every steps, gravity (g_x, g_y, g_z) in m/s2 in the plate's frame, grains
    1..n. Sorted by grain and time."""
    d = read_dump_frames(path, CONTACT_COLUMNS).rename(columns={"f_force_walls[3]": "force"})
    if d.empty:
        return pd.DataFrame({c: np.zeros(0) for c in IMPACT_COLUMNS})
    d = d.sort_values(["id", "step"], kind="stable").reset_index(drop=True)
    grain = d["id"].to_numpy(dtype=np.int64)
    step = d["step"].to_numpy(dtype=np.int64)
    touch = d["force"].to_numpy() != 0.0
    # consecutive samples of a grain: a sample apart, or two where one fell below `slowest`
    # (the turn of an impact, its normal speed passing zero)
    same = np.r_[False, (grain[1:] == grain[:-1]) & (step[1:] - step[:-1] <= 2 * sample_every)]
    before_touch = np.r_[False, touch[:-1]] & same
    onset = touch & ~before_touch
    # each contact's last sample in contact, and whether the grain is written after it
    next_same = np.r_[same[1:], False]
    next_touch = np.r_[touch[1:], False] & next_same
    last = touch & ~next_touch
    starts, ends = np.flatnonzero(onset), np.flatnonzero(last)
    if len(starts) != len(ends):  # each run of contact samples has one start and one end
        raise OutputError(f"{path}: contact samples out of order")
    g_n, g_t = -gravity[2], np.array(gravity[:2])
    vx, vy = (d[c].to_numpy() for c in ("vx", "vy"))
    t = step * dt
    wall_z = wall.wall_z if wall is not None else np.zeros_like
    wall_vz = wall.wall_vz if wall is not None else np.zeros_like
    # along the normal, relative to the plate (which a vibrating chute moves)
    vz = d["vz"].to_numpy() - wall_vz(t)
    gap = d["z"].to_numpy() - d["radius"].to_numpy() - wall_z(t)
    flight = np.r_[False, same[1:]][starts]  # the sample before is the grain's, in flight
    prev = np.maximum(starts - 1, 0)
    # free flight from the sample before to the contact (g_n > 0 towards the plate)
    v_prev = -vz[prev]
    normal = np.where(flight, np.sqrt(np.maximum(v_prev ** 2 + 2.0 * g_n * np.maximum(gap[prev], 0.0),
                                                 0.0)), -vz[starts])
    wait = np.where(flight, (normal - v_prev) / g_n if g_n > 0 else 0.0, 0.0)
    if wall is not None and getattr(wall, "amplitude", 0):
        # a moving plate: where the flight meets it, by Newton from the still plate's time
        z0, w0, t0 = d["z"].to_numpy()[prev] - d["radius"].to_numpy()[prev], d["vz"].to_numpy()[prev], t[prev]
        for _ in range(20):
            f = z0 + w0 * wait - 0.5 * g_n * wait ** 2 - wall_z(t0 + wait)
            slope = w0 - g_n * wait - wall_vz(t0 + wait)
            wait = np.clip(wait - f / np.where(slope < 0, slope, -1e-9), 0.0,
                           2 * sample_every * dt)
        normal = np.where(flight, -(w0 - g_n * wait - wall_vz(t0 + wait)), normal)
    tx = np.where(flight, vx[prev] + g_t[0] * wait, vx[starts])
    ty = np.where(flight, vy[prev] + g_t[1] * wait, vy[starts])
    tangential = np.hypot(tx, ty)
    t_onset = np.where(flight, step[prev] * dt + wait, step[starts] * dt)
    duration = (step[ends] - step[starts] + sample_every) * dt
    # not written after its last contact sample, and leaving it slower than a grain that
    # lifts off (one that lifts off leaves the `near` band unwritten too, but fast)
    sustained = ~np.r_[same[1:], False][ends] & (vz[ends] < SETTLED)
    out = pd.DataFrame({"grain": grain[starts] - 1, "time": t_onset, "normal_speed": normal,
                        "tangential_speed": tangential,
                        "angle_deg": np.degrees(np.arctan2(normal, tangential)),
                        "duration": duration, "sustained": sustained.astype(int),
                        "from_flight": flight.astype(int)})
    # a contact that begins leaving (a grain written first in contact, moving off): no impact
    out = out[out["normal_speed"] > 0].reset_index(drop=True)
    if len(out) and (out["grain"].max() >= n or out["grain"].min() < 0):
        raise OutputError(f"{path}: grain ids outside 1..{n}")
    return out


def exits(path: str, dt: float, chute_length: float, n: int) -> pd.DataFrame:
    """Each grain's exit (a row per grain, the feed's order): exited (1: its centre passed
    the chute's end), exit_time (s, when it was first written past the end: to exit_every
    steps), u (along the chute) and v (normal, m/s), exit_speed, omega (its spin about the
    axis across the chute, rad/s, the model's sign: negative rolling down-slope)."""
    d = read_dump_frames(path, EXIT_COLUMNS)
    first = d.sort_values("step", kind="stable").drop_duplicates("id")
    out = pd.DataFrame({"exited": np.zeros(n, dtype=int), "exit_time": np.nan, "u": np.nan,
                        "v": np.nan, "exit_speed": np.nan, "omega": np.nan})
    idx = first["id"].to_numpy(dtype=np.int64) - 1
    if len(idx) and (idx.max() >= n or idx.min() < 0):
        raise OutputError(f"{path}: grain ids outside 1..{n}")
    out.loc[idx, "exited"] = 1
    out.loc[idx, "exit_time"] = first["step"].to_numpy() * dt
    out.loc[idx, "u"] = first["vx"].to_numpy()
    out.loc[idx, "v"] = first["vz"].to_numpy()
    out.loc[idx, "exit_speed"] = np.hypot(first["vx"].to_numpy(), first["vz"].to_numpy())
    out.loc[idx, "omega"] = -first["omegay"].to_numpy()
    return out


# a frame with rows: its step, its count, and the header lines down to its rows (the frames
# without rows, most of a sparse dump, are never looked at)
FRAME = re.compile(rb"ITEM: TIMESTEP\n(\d+)\nITEM: NUMBER OF ATOMS\n([1-9]\d*)\n"
                   rb"ITEM: BOX BOUNDS[^\n]*\n[^\n]*\n[^\n]*\n[^\n]*\nITEM: ATOMS[^\n]*\n")


BLOCK = 1 << 26  # bytes of a dump read at a time: its whole would be parsed in copies


def read_dump_frames(path: str, columns: list[str]) -> pd.DataFrame:
    """A `dump custom` file's rows with each frame's step (its ITEM: TIMESTEP header),
    read a block of whole frames at a time, so that the memory a large dump takes is its
    numbers, not its text several times over."""
    if not os.path.exists(path):
        raise OutputError(f"{path}: missing (the LIGGGHTS run did not write it)")
    parts = []
    with open(path, "rb") as f:
        rest = b""
        while True:
            block = f.read(BLOCK)
            text = rest + block
            if block:
                # up to the last frame's start: a frame may go on into the next block
                cut = text.rfind(b"ITEM: TIMESTEP\n")
                cut = cut if cut > 0 else len(text) if not block else 0
                text, rest = text[:cut], text[cut:]
            if text:
                parts.append(parse_frames(path, text, columns))
            if not block:
                break
    parts = [p for p in parts if len(p)]
    if not parts:
        return pd.DataFrame({c: np.zeros(0) for c in ["step"] + columns})
    return pd.concat(parts, ignore_index=True) if len(parts) > 1 else parts[0]


def parse_frames(path: str, text: bytes, columns: list[str]) -> pd.DataFrame:
    """The rows of the whole frames in text, with each frame's step."""
    steps, chunks = [], []
    for m in FRAME.finditer(text):
        k = int(m.group(2))
        end = m.end()
        for _ in range(k):
            end = text.index(b"\n", end) + 1
        chunks.append(text[m.end():end])
        steps.append(np.full(k, int(m.group(1)), dtype=np.int64))
    if not chunks:
        return pd.DataFrame()
    try:
        out = pd.read_csv(io.BytesIO(b"".join(chunks)), sep=r"\s+", header=None, names=columns,
                          dtype=float, engine="c")
    except (ValueError, pd.errors.ParserError):
        raise OutputError(f"{path}: a row is not {len(columns)} numbers") from None
    out.insert(0, "step", np.concatenate(steps))
    return out


def contact_time(found: pd.DataFrame, n: int) -> np.ndarray:
    """Each grain's time in contact as the impacts measure it (s; sustained contacts to
    when the grain was last written touching)."""
    return np.bincount(found["grain"].to_numpy(dtype=np.int64), weights=found["duration"],
                       minlength=n) if len(found) else np.zeros(n)


def count(found: pd.DataFrame, n: int) -> np.ndarray:
    return np.bincount(found["grain"].to_numpy(dtype=np.int64), minlength=n) if len(found) \
        else np.zeros(n, dtype=int)

