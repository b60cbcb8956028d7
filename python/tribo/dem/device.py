"""The device a DEM run moves the grains through, and where each grain enters it.

The reference chute (docs/model.md section 9, docs/reference_case.md): a flat steel plate
`chute_length` long, tilted `tilt_deg` from the horizontal, its grains dropped from
`drop_height` above it (measured normal to the plate, as the SI FMU's gap0) at x = 0.

The LIGGGHTS scene is in the plate's frame: the plate is the plane z = 0 between x = 0
and x = chute_length, x down-slope, z along its normal, and gravity is tilted instead, g
(sin tilt, 0, -cos tilt). So every contact's normal is +z and its tangent the (x, y)
plane, and a grain has left the chute when its centre passes x = chute_length (the SI
FMU's exit, section 9). The plate is an STL mesh of two triangles: LIGGGHTS reports the
contacts of mesh walls (`compute wall/gran/local`), not of its primitive walls.

A **vibrating chute** (amplitude > 0) moves the plate along its normal, A sin(2 pi f t):
a grain meets it many times as it goes down (LIGGGHTS' `fix move/mesh ... wiggle`).

The plate is as wide as the grains' lanes need: in the dilute limit each grain has its
own lane, `lane_spacing` apart (wide enough that no two can meet: a sphere rolls and
bounces straight down a flat plate), all dropped at t = 0; at a feed rate the grains are
dropped one after another, 1/feed_rate apart, into `lanes` lanes closer together than a
grain (LANE_SPACING), in turn, each lane with ROWS drop points a grain apart along the
chute (the chute is that much shorter for them: 2.2 of the largest grain's diameters at
most), so that a grain meets its neighbours as they bounce: in a lane of its own a sphere
never catches the one before it (their motions are the same, whatever their size).
"""

import math
from dataclasses import dataclass

import numpy as np


LANE_SPACING = 0.6  # a fed stream's lanes, in the largest grain's diameter
CLEARANCE = 1.1  # how far apart grains enter, at least, in the largest grain's diameter
ROWS = 3  # a fed stream's drop points along the chute, per lane
SIDE_MARGIN = 0.03  # m: a fed stream's plate beyond its lanes, each side
ROW_SPACING = 1.1  # between them, in the largest grain's diameter


def highest_rate(lanes: int, biggest: float, spread: float) -> float:
    """The highest feed rate (grains/s) at which every grain enters clear of those that
    entered before it: each earlier grain whose drop point lies within CLEARANCE diameters
    of its own across the plate must have fallen, from rest under g, the height it needs
    below the highest entry to the lowest (`spread`, m) and clear of it. The drop points
    repeat every lanes x ROWS grains: the pairs of one period and the next say it all."""
    period = lanes * ROWS
    reach = CLEARANCE * biggest
    highest = math.inf
    for lag in range(1, 2 * period + 1):
        for i in range(period):
            j = i + lag
            dy = LANE_SPACING * biggest * abs(i % lanes - j % lanes)
            dx = ROW_SPACING * biggest * abs(i % ROWS - j % ROWS)
            apart = math.hypot(dx, dy)
            if apart >= reach:
                continue
            fall = spread + math.sqrt(reach * reach - apart * apart)
            highest = min(highest, lag / math.sqrt(2.0 * fall / 9.81))
    return highest


class DeviceError(ValueError):
    """A device that cannot be built (the message, one line, names the value)."""


def _positive(name: str, value, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
            math.isfinite(value) and value > 0):
        raise DeviceError(f"{name} = {value!r}: a positive number ({unit})")
    return float(value)


@dataclass(frozen=True)
class Chute:
    """The reference chute in the plate's frame (see the module's text)."""

    chute_length: float = 0.3
    tilt_deg: float = 30.0
    amplitude: float = 0.0  # m: the plate's vibration along its normal (0: at rest)
    frequency: float = 0.0  # Hz

    def __post_init__(self):
        _positive("chute_length", self.chute_length, "m")
        if not (isinstance(self.tilt_deg, (int, float)) and 0 < self.tilt_deg < 90):
            raise DeviceError(f"tilt_deg = {self.tilt_deg!r}: the chute's tilt from the "
                              f"horizontal, degrees, in (0, 90)")
        if self.amplitude:
            _positive("vibration amplitude", self.amplitude, "m, below 0.01")
            _positive("vibration frequency", self.frequency, "Hz, up to 1000")
            if self.amplitude >= 0.01 or self.frequency > 1000:
                raise DeviceError(f"vibration {self.amplitude:g} m at {self.frequency:g} Hz: "
                                  f"an amplitude below 0.01 m, a frequency up to 1000 Hz")

    def wall_z(self, t):
        """The plate's height along its normal at time t (s): A sin(2 pi f t), the
        LIGGGHTS `wiggle` of the mesh from t = 0."""
        return self.amplitude * np.sin(2.0 * math.pi * self.frequency * np.asarray(t, dtype=float))

    def wall_vz(self, t):
        w = 2.0 * math.pi * self.frequency
        return self.amplitude * w * np.cos(w * np.asarray(t, dtype=float))

    @property
    def gravity_vector(self) -> tuple:
        t = math.radians(self.tilt_deg)
        return (math.sin(t), 0.0, -math.cos(t))

    def drop_velocity(self, speed: np.ndarray, angle_deg: np.ndarray) -> np.ndarray:
        """A drop's velocity in the plate's frame: `speed` in the direction `angle_deg`
        from the vertical, positive towards down-slope (docs/model.md section 9:
        U = s sin(tilt + angle), V = -s cos(tilt + angle))."""
        a = np.radians(self.tilt_deg + np.asarray(angle_deg, dtype=float))
        s = np.asarray(speed, dtype=float)
        return np.stack([s * np.sin(a), np.zeros_like(s), -s * np.cos(a)], axis=-1)

    def stl(self, width: float) -> str:
        """The plate, x in [0, L], y in [-width/2, width/2], z = 0, normal +z, as ASCII STL."""
        L, h = self.chute_length, width / 2.0
        corners = [(0.0, -h), (L, -h), (L, h), (0.0, h)]
        lines = ["solid plate"]
        for tri in ((0, 1, 2), (0, 2, 3)):
            lines += ["  facet normal 0 0 1", "    outer loop"]
            lines += [f"      vertex {corners[i][0]:.9g} {corners[i][1]:.9g} 0" for i in tri]
            lines += ["    endloop", "  endfacet"]
        return "\n".join(lines + ["endsolid plate", ""])


@dataclass(frozen=True)
class Entry:
    """Where and when each grain enters: x, y, z of its centre (m), its velocity (m/s),
    its drop time (s), in the plate's frame; and the plate's width (m)."""

    position: np.ndarray  # (n, 3)
    velocity: np.ndarray  # (n, 3)
    time: np.ndarray      # (n,)
    width: float


def entries(chute: Chute, size: np.ndarray, drop_height: np.ndarray, drop_speed: np.ndarray,
            drop_angle_deg: np.ndarray, feed_rate: float | None, lanes: int | None,
            lane_spacing: float | None = None) -> Entry:
    """The grains' entries (the module's text): diameters `size` (spheres), each dropped
    from drop_height (its lowest point above the plate, normal to it) at x = 0. feed_rate
    None: the dilute limit, a lane each, `lane_spacing` apart (default three of the largest
    grain); else grains/s into `lanes` lanes (default 5)."""
    size = np.asarray(size, dtype=float)
    n = len(size)
    biggest = float(size.max())
    z = size / 2.0 + np.asarray(drop_height, dtype=float)
    velocity = chute.drop_velocity(drop_speed, drop_angle_deg)
    if feed_rate is None:
        spacing = 3.0 * biggest if lane_spacing is None else _positive(
            "lane_spacing", lane_spacing, "m")
        if spacing < 1.5 * biggest:
            raise DeviceError(f"lane_spacing = {spacing:g} m: at least 1.5 times the largest "
                              f"grain ({1.5 * biggest:g} m), so that neighbours cannot meet")
        width = n * spacing
        y = -width / 2.0 + spacing * (np.arange(n) + 0.5)
        time = np.zeros(n)
    else:
        rate = _positive("feed_rate", feed_rate, "grains/s")
        count = 5 if lanes is None else lanes
        if isinstance(count, bool) or not isinstance(count, int) or count < 1:
            raise DeviceError(f"lanes = {lanes!r}: a whole number, at least 1")
        # lanes closer than a grain (LANE_SPACING of the largest): grains of neighbouring
        # lanes overlap across the chute, so that they meet. Each lane has ROWS drop points
        # along the chute, a grain apart, taken in turn with the lanes (ROWS and the lanes
        # share no factor but 1), so that consecutive grains enter clear of each other
        spacing = LANE_SPACING * biggest
        # the plate is wider than the lanes by SIDE_MARGIN each side: grains knocked
        # sideways stay on it, as between a chute's side walls (which are not modelled)
        width = count * spacing + 2.0 * SIDE_MARGIN
        i = np.arange(n)
        y = -count * spacing / 2.0 + spacing * (i % count + 0.5)
        x = ROW_SPACING * biggest * (i % ROWS)
        highest = highest_rate(count, biggest, float(np.max(z) - np.min(z)))
        if rate > highest:
            raise DeviceError(f"feed_rate = {rate:g} grains/s: at most {highest:.4g} with "
                              f"{count} lanes of {biggest:g} m grains dropped from heights "
                              f"{float(np.max(z) - np.min(z)):g} m apart (a grain enters only "
                              f"where the ones before have fallen clear)")
        time = i / rate
        position = np.stack([x, y, z], axis=-1)
        return Entry(position, velocity, time, width)
    position = np.stack([np.zeros(n), y, z], axis=-1)
    return Entry(position, velocity, time, width)
