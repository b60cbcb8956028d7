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

A **vibrating chute**, a vibratory feeder (amplitude > 0, docs/model.md section 9b), moves
the plate and its side walls along a stroke at `angle_deg` to the plate's down-slope axis
(90: along its normal), A sin(2 pi f t) (cos psi, sin psi) in the plate's axes (LIGGGHTS'
`fix move/mesh ... wiggle`): a grain meets it many times, and a stroke inclined forward
throws it forward at each hop, conveying it on a level plate too (tilt 0, taken only
vibrating). The **side walls** along the plate (`sides_stl`), as high as the box, hold the
grains on it; their impacts are charged like the plate's and counted apart. A **back wall**
across the plate where it begins (behind the drop points: `start`), as high, holds the
grains a fed stream knocks backwards (without it a third of them fell off behind); its
impacts are not read (contacts.py reads the plate's and the sides').

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
    amplitude: float = 0.0  # m: the plate's stroke (0: at rest)
    frequency: float = 0.0  # Hz
    angle_deg: float = 90.0  # the stroke's angle from the plate's down-slope axis (90: its normal)

    def __post_init__(self):
        _positive("chute_length", self.chute_length, "m")
        if not (isinstance(self.tilt_deg, (int, float)) and 0 <= self.tilt_deg < 90):
            raise DeviceError(f"tilt_deg = {self.tilt_deg!r}: the chute's tilt from the "
                              f"horizontal, degrees, in [0, 90)")
        if self.amplitude:
            _positive("vibration amplitude", self.amplitude, "m, below 0.01")
            _positive("vibration frequency", self.frequency, "Hz, up to 1000")
            if self.amplitude >= 0.01 or self.frequency > 1000:
                raise DeviceError(f"vibration {self.amplitude:g} m at {self.frequency:g} Hz: "
                                  f"an amplitude below 0.01 m, a frequency up to 1000 Hz")
            if not (isinstance(self.angle_deg, (int, float)) and 0 < self.angle_deg <= 90):
                raise DeviceError(f"vibration angle = {self.angle_deg!r}: the stroke's angle "
                                  f"from the plate, degrees, in (0, 90]")
        elif self.tilt_deg == 0:
            raise DeviceError("tilt_deg = 0: a level chute conveys only when it vibrates "
                              "(give --vibration, or a tilt in (0, 90) degrees)")

    @property
    def stroke(self) -> tuple:
        """The stroke's amplitude along the plate's axes (x down-slope, z its normal), m:
        A (cos psi, sin psi) (docs/model.md section 9b)."""
        psi = math.radians(self.angle_deg)
        # exactly along the normal at 90 degrees (cos 90 degrees is 6e-17, not 0)
        return (0.0 if self.angle_deg == 90 else self.amplitude * math.cos(psi),
                self.amplitude * math.sin(psi))

    def displacement(self, t):
        """The plate's displacement (x, z) at time t (s): the stroke times sin(2 pi f t), the
        LIGGGHTS `wiggle` of the meshes from t = 0."""
        s = np.sin(2.0 * math.pi * self.frequency * np.asarray(t, dtype=float))
        return self.stroke[0] * s, self.stroke[1] * s

    def velocity(self, t):
        """The plate's velocity (x, z) at time t (s)."""
        w = 2.0 * math.pi * self.frequency
        c = w * np.cos(w * np.asarray(t, dtype=float))
        return self.stroke[0] * c, self.stroke[1] * c

    def wall_z(self, t):
        """The plate's height along its normal at time t (s)."""
        return self.displacement(t)[1]

    def wall_vz(self, t):
        return self.velocity(t)[1]

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

    def start(self, biggest: float) -> float:
        """Where the plate begins (m): at the drop point, x = 0, or behind it by the
        stroke along the plate and a grain, so that a feeder's plate is under every grain it
        drops whatever its phase."""
        return -(abs(self.stroke[0]) + biggest) if self.amplitude else 0.0

    def stl(self, width: float, start: float = 0.0) -> str:
        """The plate, x in [start, L], y in [-width/2, width/2], z = 0, normal +z, as ASCII
        STL."""
        L, h, x0 = self.chute_length, width / 2.0, start
        return _stl("plate", [((x0, -h, 0.0), (L, -h, 0.0), (L, h, 0.0), (x0, h, 0.0))])

    def sides_stl(self, width: float, height: float, start: float = 0.0) -> str:
        """The side walls along the plate, y = -width/2 and y = width/2, x in [start, L], z
        in [0, height], and the back wall across it at x = start, facing into the chute, as
        ASCII STL."""
        L, h, x0 = self.chute_length, width / 2.0, start
        return _stl("sides", [((x0, -h, 0.0), (x0, -h, height), (L, -h, height), (L, -h, 0.0)),
                              ((x0, h, 0.0), (L, h, 0.0), (L, h, height), (x0, h, height)),
                              ((x0, -h, 0.0), (x0, h, 0.0), (x0, h, height), (x0, -h, height))])


def _stl(name: str, quads) -> str:
    """Rectangles (four corners each, anticlockwise seen from the side they face) as two
    triangles each, in ASCII STL."""
    lines = [f"solid {name}"]
    for corners in quads:
        a, b, c = (np.array(corners[i]) for i in (0, 1, 2))
        normal = np.cross(b - a, c - a)
        normal = normal / np.linalg.norm(normal)
        for tri in ((0, 1, 2), (0, 2, 3)):
            lines += ["  facet normal " + " ".join(f"{v:.9g}" for v in normal + 0.0),
                      "    outer loop"]
            lines += ["      vertex " + " ".join(f"{v:.9g}" for v in corners[i]) for i in tri]
            lines += ["    endloop", "  endfacet"]
    return "\n".join(lines + [f"endsolid {name}", ""])


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
