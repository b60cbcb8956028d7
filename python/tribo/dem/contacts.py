"""The grain-wall impacts and the exits, read from a LIGGGHTS run's outputs (script.py).

**Sampling.** contacts.dump holds, every `sample_every` steps (the fastest impact's Hertz
contact time over 1.1 on a feeder, over 1.5 on a still chute: script.py), each grain whose
gap to the plate is below `near` (twice what the fastest grain covers in a sample) and
whose normal speed relative to it exceeds `slowest` or whom it presses on with more than
script.PRESSED times its weight (an impact's turn); the wall's normal force on it says
whether it touches. So every impact has at least one sample in flight just before it and
one in contact: none is missed (a contact shorter than a sample interval would be shorter
than the fastest impact's; compare_impacts checks it against a reference written every
step beside it). A feeder's holds the same for its side walls too, across the chute: a
grain near the plate or a side wall, with the force along both normals (LIGGGHTS' one wall
fix sums the plate's and the sides': a sample touches a wall where that wall's component
is nonzero and the grain's gap to it is below TOUCHING).

**Against the moving wall.** Each sample is read in the wall's own axes (`Wall`): its gap
to the wall and its velocity along the wall's normal and along the wall, each less the
wall's (a vibrating chute moves the plate and its sides along the stroke, device.py): so an
impact's normal and tangential speeds are those relative to the wall, as the map takes them.

**An impact** is a grain's first sample in contact after a sample in flight (or after
none: a grain that entered touching). Its onset is the free flight from the sample
before carried to the contact (gravity alone acts in flight): on a still wall `v_n =
sqrt(v^2 + 2 g_n gap)`, g_n gravity towards it; on a moving one the time the flight meets
the wall, by Newton's method from the still wall's, and the speeds there relative to it;
the tangential velocity advanced by gravity along the wall over the same time. Without a
sample in flight (a grain written first in contact) the onset is the first contact sample's
velocity (`from_flight` = 0 says so). Its duration runs to its last sample in contact, to a
sample interval; a contact whose grain stops being written while it still touches, leaving
it slower than SETTLED (it rests or rolls on the plate: normal speed below `slowest`) is
`sustained`, its duration then a lower bound.

**Read in a stream.** A dump is read a block of frames at a time (BLOCK bytes), in time
order; a block's contacts that have ended are read off, and only what a later block needs is
carried into it: each grain's last sample (where the next may follow it), and the samples of
a contact still going on from the one in flight before it. So the memory the reading takes
is a block's samples and the grains on the device, not the run's.

Per impact (`impacts`): grain (0-based, the feed's order), time (s, the onset), normal
and tangential speed (m/s), angle (degrees from the wall's surface, 90 head-on),
duration (s), sustained, from_flight.
"""

import io
import math
import os
import re
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .script import CONTACT_COLUMNS, EXIT_COLUMNS, FEEDER_COLUMNS

SETTLED = 1e-2  # m/s: a contact left slower than this along the normal is sustained
IMPACT_COLUMNS = ["grain", "time", "normal_speed", "tangential_speed", "angle_deg",
                  "duration", "sustained", "from_flight"]
NEWTON_STEPS = 20  # the flight's meeting with a moving wall
# m: a grain touches a wall where its gap is below this (a contact's is its indentation,
# negative; the dumps' numbers are read to a nanometre, script.py)
TOUCHING = 1e-8


class OutputError(ValueError):
    """A LIGGGHTS output that cannot be read (the message names the file)."""


@dataclass(frozen=True)
class Wall:
    """How a dump's samples are read against one wall (the module's text): the plate
    (normal +z) or the side walls (normal across the chute, +-y, at y = -+half_width),
    moving with `chute` (device.Chute: its stroke; None: still), gravity (g_x, g_y, g_z) in
    m/s2 in the plate's frame."""

    gravity: tuple
    chute: object = None
    side: bool = False
    half_width: float = 0.0
    others: bool = False  # the dump's force is also other walls' (a feeder's plate and sides)

    @property
    def columns(self) -> list[str]:
        """The dump's columns (script.py): a feeder's (`others`) or a still chute's."""
        return FEEDER_COLUMNS if self.others else CONTACT_COLUMNS

    @property
    def force(self) -> str:
        """The column of the walls' force along this one's normal."""
        return "f_force_walls[2]" if self.side else "f_force_walls[3]"

    def moving(self) -> bool:
        return self.chute is not None and bool(getattr(self.chute, "amplitude", 0))

    def position(self, t):
        """The wall's displacement along its normal (m) at t: the plate's stroke along z;
        the stroke moves the side walls along themselves."""
        if self.side or not self.moving():
            return np.zeros_like(np.asarray(t, dtype=float))
        return self.chute.displacement(t)[1]

    def speed(self, t):
        """(along its normal, along it 1, along it 2), the wall's velocity (m/s) at t."""
        t = np.asarray(t, dtype=float)
        zero = np.zeros_like(t)
        if not self.moving():
            return zero, zero, zero
        vx, vz = self.chute.velocity(t)
        vx, vz = vx + zero, vz + zero
        return (zero, vx, vz) if self.side else (vz, vx, zero)

    def local(self, d: pd.DataFrame):
        """Each sample in the wall's axes: its gap to the wall at rest (m), its velocity
        along the wall's normal (away from it) and along the wall (two components), absolute,
        and gravity's components (towards the wall; along it)."""
        g = self.gravity
        r = d["radius"].to_numpy()
        if not self.side:
            return (d["z"].to_numpy() - r, d["vz"].to_numpy(), d["vx"].to_numpy(),
                    d["vy"].to_numpy(), -g[2], (g[0], g[1]))
        # the side a grain is near: the one on its own side of the axis; its normal inwards
        # (gravity, in the plate's x-z plane, has no component across the chute)
        y = d["y"].to_numpy()
        inward = np.where(y > 0, -1.0, 1.0)
        return (self.half_width - np.abs(y) - r, inward * d["vy"].to_numpy(),
                d["vx"].to_numpy(), d["vz"].to_numpy(), 0.0, (g[0], g[2]))


def impacts(path: str, dt: float, sample_every: int, gravity: tuple, n: int,
            wall=None) -> pd.DataFrame:
    """The impacts (the module's text) of contacts.dump against the plate (or a feeder's side
    walls, `wall` a Wall of side=True), a run of time step dt (s) sampled every sample_every steps, gravity
    (g_x, g_y, g_z) in m/s2 in the plate's frame, grains 1..n; `wall` a Wall, or the chute
    (device.Chute) whose plate it is, or None (a still plate). Sorted by grain and time."""
    if not isinstance(wall, Wall):
        wall = Wall(tuple(gravity), wall, others=bool(getattr(wall, "amplitude", 0)))
    return walls_impacts(path, dt, sample_every, [wall], n)[0]


def walls_impacts(path: str, dt: float, sample_every: int, walls: list, n: int,
                  joined: int | None = None) -> list:
    """The impacts against each of `walls` (Walls of one dump's columns: a feeder's plate and
    side walls) as `impacts` reads them, the dump read once for all. joined: two samples of
    a grain this many steps apart or less are consecutive (default two sample intervals: a
    contact's samples either side of its turn, slower than `slowest`, unwritten); a dense
    reference is read with its sampling's, so that a contact is joined across the same
    turn (compare_impacts)."""
    joined = 2 * sample_every if joined is None else joined
    columns = walls[0].columns
    if any(w.columns != columns for w in walls):
        raise ValueError("walls: each read from the same dump's columns")
    parts, carry = [[] for _ in walls], [None] * len(walls)
    for block, last_step, final in dump_blocks(path, columns):
        for k, wall in enumerate(walls):
            d = block if carry[k] is None else pd.concat([carry[k], block], ignore_index=True)
            if d.empty:
                continue
            found, carry[k] = _block_impacts(path, d, dt, sample_every, wall, last_step, final,
                                             joined)
            parts[k].append(found)
    return [_sorted(path, found, n) for found in parts]


def _sorted(path: str, parts: list, n: int) -> pd.DataFrame:
    """A wall's impacts from its blocks' (the module's text), sorted by grain and time."""
    out = (pd.concat(parts, ignore_index=True) if parts
           else pd.DataFrame({c: np.zeros(0) for c in IMPACT_COLUMNS}))
    # a contact that begins leaving (a grain written first in contact, moving off): no impact
    out = out[out["normal_speed"] > 0]
    out = out.sort_values(["grain", "time"], kind="stable").reset_index(drop=True).astype(
        {"grain": np.int64, "sustained": int, "from_flight": int})
    if len(out) and (out["grain"].max() >= n or out["grain"].min() < 0):
        raise OutputError(f"{path}: grain ids outside 1..{n}")
    return out


def _block_impacts(path, d, dt, sample_every, wall: Wall, last_step: int, final: bool,
                   close: int):
    """The impacts of the contacts that have ended among samples `d` (the samples carried
    and a block's), and the samples a later block needs (the module's text); two samples of
    a grain `close` steps apart or less are consecutive."""
    force = wall.force
    d = d.sort_values(["id", "step"], kind="stable").reset_index(drop=True)
    grain = d["id"].to_numpy(dtype=np.int64)
    step = d["step"].to_numpy(dtype=np.int64)
    t = step * dt
    gap_rest, v_abs, t1_abs, t2_abs, g_n, g_t = wall.local(d)
    gap = gap_rest - wall.position(t)
    touch = d[force].to_numpy() != 0.0
    if wall.others:
        # the force is every wall's (script.py): touching this one only where it is reached
        # (the other's friction has a component along this one's normal)
        touch &= gap < TOUCHING
    # consecutive samples of a grain: a sample apart, or two where one fell below `slowest`
    # (the turn of an impact, its normal speed passing zero)
    same = np.r_[False, (grain[1:] == grain[:-1]) & (step[1:] - step[:-1] <= close)]
    before_touch = np.r_[False, touch[:-1]] & same
    onset = touch & ~before_touch
    # each contact's last sample in contact, and whether the grain is written after it
    next_same = np.r_[same[1:], False]
    next_touch = np.r_[touch[1:], False] & next_same
    last = touch & ~next_touch
    starts, ends = np.flatnonzero(onset), np.flatnonzero(last)
    if len(starts) != len(ends):  # each run of contact samples has one start and one end
        raise OutputError(f"{path}: contact samples out of order")
    flight = same[starts]  # the sample before is the grain's, in flight
    # a contact at a grain's last sample may go on in the next block: carried, not read yet
    tail = np.r_[grain[1:] != grain[:-1], True]
    going_on = tail[ends] & (not final) & (last_step - step[ends] <= close)
    # what the next block needs: a contact going on from the sample before it, else a
    # grain's last sample where the next may follow it
    group = np.cumsum(np.r_[True, grain[1:] != grain[:-1]]) - 1
    tails = np.flatnonzero(tail)
    keep_from = np.where(last_step - step[tails] <= close, tails, len(d)) if not final \
        else np.full(len(tails), len(d))
    keep_from[group[ends[going_on]]] = np.where(flight[going_on], starts[going_on] - 1,
                                                starts[going_on])
    carry = d[np.arange(len(d)) >= keep_from[group]]
    done = ~going_on
    starts, ends, flight = starts[done], ends[done], flight[done]
    v_wall = wall.speed(t)[0]
    vn = v_abs - v_wall  # along the normal, relative to the wall
    prev = np.maximum(starts - 1, 0)
    # free flight from the sample before to the contact (g_n > 0 towards the wall)
    v_prev = -vn[prev]
    normal = np.where(flight, np.sqrt(np.maximum(
        v_prev ** 2 + 2.0 * g_n * np.maximum(gap[prev], 0.0), 0.0)), -vn[starts])
    # the flight's time (without gravity towards the wall, a side's: its gap at its speed)
    if g_n > 0:
        wait = np.where(flight, (normal - v_prev) / g_n, 0.0)
    else:
        wait = np.where(flight & (v_prev > 0), np.maximum(gap[prev], 0.0)
                        / np.where(v_prev > 0, v_prev, 1.0), 0.0)
    if wall.moving():
        # a moving wall: where the flight meets it, by Newton from the still wall's time
        z0, w0, t0 = gap_rest[prev], v_abs[prev], t[prev]
        for _ in range(NEWTON_STEPS):
            f = z0 + w0 * wait - 0.5 * g_n * wait ** 2 - wall.position(t0 + wait)
            slope = w0 - g_n * wait - wall.speed(t0 + wait)[0]
            wait = np.clip(wait - f / np.where(slope < 0, slope, -1e-9), 0.0, close * dt)
        normal = np.where(flight, -(w0 - g_n * wait - wall.speed(t0 + wait)[0]), normal)
    _, t1_at, t2_at = wall.speed(np.where(flight, t[prev] + wait, t[starts]))
    tx = np.where(flight, t1_abs[prev] + g_t[0] * wait, t1_abs[starts]) - t1_at
    ty = np.where(flight, t2_abs[prev] + g_t[1] * wait, t2_abs[starts]) - t2_at
    tangential = np.hypot(tx, ty)
    t_onset = np.where(flight, t[prev] + wait, t[starts])
    duration = (step[ends] - step[starts] + sample_every) * dt
    # not written after its last contact sample, and leaving it slower than a grain that
    # lifts off (one that lifts off leaves the `near` band unwritten too, but fast)
    sustained = ~next_same[ends] & (vn[ends] < SETTLED)
    found = pd.DataFrame({"grain": grain[starts] - 1, "time": t_onset, "normal_speed": normal,
                          "tangential_speed": tangential,
                          "angle_deg": np.degrees(np.arctan2(normal, tangential)),
                          "duration": duration, "sustained": sustained.astype(int),
                          "from_flight": flight.astype(int)})
    return found, carry.reset_index(drop=True)


def exits(path: str, dt: float, chute_length: float, n: int) -> pd.DataFrame:
    """Each grain's exit (a row per grain, the feed's order): exited (1: its centre passed
    the chute's end), exit_time (s, when it was first written past the end: to exit_every
    steps), u (along the chute) and v (normal, m/s), exit_speed, omega (its spin about the
    axis across the chute, rad/s, the model's sign: negative rolling down-slope). Read in a
    stream: a block's first sample of each grain."""
    firsts = [block.drop_duplicates("id") for block, _, _ in dump_blocks(path, EXIT_COLUMNS)
              if len(block)]
    first = (pd.concat(firsts, ignore_index=True).drop_duplicates("id") if firsts
             else pd.DataFrame({c: np.zeros(0) for c in ["step"] + EXIT_COLUMNS}))
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
STEP = re.compile(rb"ITEM: TIMESTEP\n(\d+)\n")


BLOCK = 1 << 24  # bytes of a dump read at a time: a block's samples are what is held


def dump_blocks(path: str, columns: list[str]):
    """A `dump custom` file a block of whole frames at a time, in the file's (time) order:
    (its rows with each frame's step, the last step it has a frame of, whether it is the
    last block)."""
    if not os.path.exists(path):
        raise OutputError(f"{path}: missing (the LIGGGHTS run did not write it)")
    empty = pd.DataFrame({c: np.zeros(0) for c in ["step"] + columns})
    last_step = -1
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
                header = text.rfind(b"ITEM: TIMESTEP\n")
                m = STEP.match(text, header) if header >= 0 else None
                last_step = int(m.group(1)) if m else last_step
                rows = parse_frames(path, text, columns)
                yield (rows if len(rows) else empty), last_step, not block
            elif not block:
                yield empty, last_step, True
            if not block:
                break


def read_dump_frames(path: str, columns: list[str]) -> pd.DataFrame:
    """A `dump custom` file's rows with each frame's step (its ITEM: TIMESTEP header),
    read a block of whole frames at a time (dump_blocks)."""
    parts = [rows for rows, _, _ in dump_blocks(path, columns) if len(rows)]
    if not parts:
        return pd.DataFrame({c: np.zeros(0) for c in ["step"] + columns})
    return pd.concat(parts, ignore_index=True) if len(parts) > 1 else parts[0]


def parse_frames(path: str, text: bytes, columns: list[str]) -> pd.DataFrame:
    """The rows of the whole frames in text, with each frame's step."""
    steps, counts, chunks = [], [], []
    for m in FRAME.finditer(text):
        k = int(m.group(2))
        end = m.end()
        for _ in range(k):
            end = text.index(b"\n", end) + 1
        chunks.append(text[m.end():end])
        steps.append(int(m.group(1)))
        counts.append(k)
    if not chunks:
        return pd.DataFrame()
    try:
        out = pd.read_csv(io.BytesIO(b"".join(chunks)), sep=r"\s+", header=None, names=columns,
                          dtype=float, engine="c")
    except (ValueError, pd.errors.ParserError):
        raise OutputError(f"{path}: a row is not {len(columns)} numbers") from None
    out.insert(0, "step", np.repeat(np.array(steps, dtype=np.int64), counts))
    return out


def contact_time(found: pd.DataFrame, n: int) -> np.ndarray:
    """Each grain's time in contact as the impacts measure it (s; sustained contacts to
    when the grain was last written touching)."""
    return np.bincount(found["grain"].to_numpy(dtype=np.int64), weights=found["duration"],
                       minlength=n) if len(found) else np.zeros(n)


def count(found: pd.DataFrame, n: int) -> np.ndarray:
    return np.bincount(found["grain"].to_numpy(dtype=np.int64), minlength=n) if len(found) \
        else np.zeros(n, dtype=int)


def compare_impacts(found: pd.DataFrame, reference: pd.DataFrame,
                    interval: float) -> pd.DataFrame:
    """The impacts `found` by a run's sampling against those of a dense `reference` written
    beside it in the same run (script.REFERENCE), impact by impact: each reference impact
    (a row, its grain, wall, time, normal_speed) with the found one of the same grain and wall
    whose onset is nearest its own within `interval` (s, the sampling's: the onsets of both
    are the flight before carried on, so that they agree far closer), or none (`missed`);
    then the found impacts no reference impact matched (`extra`). Columns: grain, wall,
    time, normal_speed (the reference's; the found one's where there is none), dt and
    dv_n (found less reference), missed, extra, and sustained_differs (1 where the two
    read the contact's end differently: a slow contact's, interval-dependent, docs/dem.md).
    """
    keys, kept = ["grain", "wall"], ["time", "normal_speed", "sustained"]
    ref = reference[keys + kept].astype({"grain": np.int64, "wall": np.int64})
    got = found[keys + kept].astype({"grain": np.int64, "wall": np.int64})
    ref = ref.sort_values("time", kind="stable").reset_index(drop=True)
    got = got.sort_values("time", kind="stable").reset_index(drop=True)
    got["found"] = np.arange(len(got))
    matched = pd.merge_asof(ref, got.rename(columns={"time": "time_found",
                                                     "normal_speed": "speed_found",
                                                     "sustained": "sustained_found"}),
                            left_on="time", right_on="time_found", by=keys,
                            direction="nearest", tolerance=interval)
    # a found impact matched twice is one of them: the nearer keeps it
    taken = matched["found"].notna()
    gap = (matched["time_found"] - matched["time"]).abs()
    twice = matched[taken].assign(gap=gap[taken]).sort_values("gap", kind="stable").duplicated(
        "found", keep="first")
    matched.loc[twice[twice].index, ["found", "time_found", "speed_found"]] = np.nan
    taken = matched["found"].notna()
    out = pd.DataFrame({"grain": matched["grain"], "wall": matched["wall"],
                        "time": matched["time"], "normal_speed": matched["normal_speed"],
                        "dt": matched["time_found"] - matched["time"],
                        "dv_n": matched["speed_found"] - matched["normal_speed"],
                        "missed": (~taken).astype(int), "extra": 0,
                        "sustained_differs": (taken & (matched["sustained_found"]
                                                       != matched["sustained"])).astype(int)})
    left = got[~got["found"].isin(matched.loc[taken, "found"])]
    extra = pd.DataFrame({"grain": left["grain"], "wall": left["wall"], "time": left["time"],
                          "normal_speed": left["normal_speed"], "dt": np.nan, "dv_n": np.nan,
                          "missed": 0, "extra": 1, "sustained_differs": 0})
    return pd.concat([out, extra], ignore_index=True).sort_values(
        ["grain", "wall", "time"], kind="stable").reset_index(drop=True)
