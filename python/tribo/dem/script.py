"""The LIGGGHTS input of a DEM run: the device (device.py), the materials, the contact law,
the grains as they enter, and the two outputs the charging reads.

The contact law is LIGGGHTS' Hertz-Mindlin (`hertz tangential history`, rolling friction
`cdt`) with the pair's Young's moduli and Poisson's ratios (tribo.materials, times
`stiffness_scale`), the normal restitution e of the project's own model (what an impact
of its grain gives: charging.py) and its friction mu and rolling resistance mu_roll
(docs/model.md sections 3, 3c): the grains bounce and roll as the model's grain does, to
what a sphere can do. Grain-grain contacts take the same law: LIGGGHTS moves the grains
through each other's collisions; they exchange no charge. `hard_particles yes`: LIGGGHTS
refuses Young's moduli above 1e9 Pa in SI units without it.

The time step is a fraction of the smallest grain's Rayleigh time and of its Hertz contact
time at the fastest impact (`time_step`); the wall contacts are written every
`sample_every` steps, that contact time over 1.1 (a still chute's: over 1.5), so that
every contact is seen in contact at least once (a slower one lasts longer) and every
impact has a sample in flight before it (contacts.py reads them;
scripts/check_dem_sampling.sh checks it against a reference written every step beside
it, REFERENCE).

Outputs (the run's folder):

    contacts.dump  every sample_every steps, each grain near the plate and moving along its
                   normal: the step, its id, position, velocity, radius, and the wall's
                   normal force on it (LIGGGHTS' wall contact: nonzero while touching)
                   (a feeder's: near the plate or near a side wall, moving across the
                   chute, with the walls' force across it too, to 10 digits)
    reference.dump the same grains every reference_every steps, where asked (the check)
    exits.dump     every exit_every steps, the grains whose centre has passed the chute's
                   end (x > chute_length): id, position, velocity, spin
    log.liggghts   LIGGGHTS' log; its thermo lines (step, grains in the box) show progress
"""

import math
from dataclasses import dataclass

import numpy as np

from .device import Chute, Entry

INPUT, PLATE, SIDES, LOG = "in.liggghts", "plate.stl", "sides.stl", "log.liggghts"
CONTACTS, EXITS, REFERENCE = "contacts.dump", "exits.dump", "reference.dump"
# the columns contacts.dump holds (each frame headed by its step): the grain's id, centre, velocity and radius,
# and the normal component of the force the wall exerts on it (fix wall/gran's
# store_force: nonzero while the grain touches the wall)
CONTACT_COLUMNS = ["id", "x", "y", "z", "vx", "vy", "vz", "radius", "f_force_walls[3]"]
# a feeder's contacts.dump: also the force across the chute (the side walls' normal)
FEEDER_COLUMNS = CONTACT_COLUMNS[:-1] + ["f_force_walls[2]", "f_force_walls[3]"]
# its numbers to 10 digits: a grain's gap to a side wall centimetres off the axis is read
# to a nanometre (the default 6 digits: to 0.1 um, more than a contact's indentation)
FEEDER_FORMAT = "%d " + " ".join(["%.10g"] * (len(FEEDER_COLUMNS) - 1))
EXIT_COLUMNS = ["id", "x", "y", "z", "vx", "vy", "vz", "omegay"]
# a tenth of the smallest grain's Rayleigh time: LIGGGHTS warns above a fifth of it
RAYLEIGH_FRACTION = 0.1
STEPS_PER_CONTACT = 40  # the time step: the fastest impact's Hertz contact time over this
# the contacts' sampling: this many samples in the fastest impact's contact, at least one
# in every contact. The onset is the flight before it carried on to the wall, exact at any
# interval (contacts.py); a sample costs LIGGGHTS the same whatever it holds, so that on a
# feeder, its grains in flight most of the time, the fewer the cheaper (docs/dem.md). The
# margin: a contact lasts longer than its Hertz time (LIGGGHTS' damping), and the shorter
# the faster the impact only as its speed to the -1/5: an interval a tenth shorter than
# the fastest estimated impact's contact still sees one 1.6 times as fast (measured on the
# feeder of docs/dem.md: its shortest contact 43 steps, a sample every 36)
SAMPLES_PER_CONTACT = 1.1
# a still chute's: its grains settle and roll, and a contact's end is read as sustained
# from when its grain stops being written, which the interval moves (measured on 12 grains
# of docs/dem.md's dilute run: 28 sustained contacts of 221 at 26 steps, 20 at 36); kept
# where its results were made (a still chute's grains are in flight little: the sampling
# costs it little)
STILL_SAMPLES_PER_CONTACT = 1.5
# a grain in contact is written, however slowly it moves along the normal, while the wall
# presses on it with more than this many times its weight: an impact's turn (a grain at
# rest on a plate is pressed with its weight, twice at most on a feeder that does not
# throw it)
PRESSED = 10.0
# the most steps a run takes: LIGGGHTS' `run N` takes N up to 2^31 - 1 (a run is cut into
# pieces of a two-hundredth of its steps, so this leaves a factor of 200 for the step
# being shorter than the Rayleigh bound the horizon is checked with)
MAX_STEPS = 2**31 - 1
# the contact law: the words after `model` in the grains' pair style and in the wall's fix
# (the module's text); another law is for comparing with the project's own (docs/dem.md,
# the feeder beside the project's population), with the properties it reads
LAW = "hertz tangential history rolling_friction cdt"


@dataclass(frozen=True)
class Contact:
    """The contact law's constants (the module's text); moduli in Pa."""

    youngs_particle: float
    poisson_particle: float
    youngs_wall: float
    poisson_wall: float
    density: float
    restitution: float
    friction: float
    rolling_friction: float

    @property
    def effective_modulus(self) -> float:
        return effective_modulus(self.youngs_particle, self.poisson_particle,
                                 self.youngs_wall, self.poisson_wall)


def effective_modulus(youngs_particle: float, poisson_particle: float, youngs_wall: float,
                      poisson_wall: float) -> float:
    """E* of a grain on the wall (Pa): 1 / ((1 - nu_p^2)/E_p + (1 - nu_w^2)/E_w)."""
    return 1.0 / ((1.0 - poisson_particle ** 2) / youngs_particle
                  + (1.0 - poisson_wall ** 2) / youngs_wall)


def rayleigh_time(diameter: float, c: Contact) -> float:
    """The Rayleigh wave's time across a grain: pi r sqrt(rho/G) / (0.1631 nu + 0.8766)."""
    shear = c.youngs_particle / (2.0 * (1.0 + c.poisson_particle))
    return (math.pi * diameter / 2.0 * math.sqrt(c.density / shear)
            / (0.1631 * c.poisson_particle + 0.8766))


def hertz_time(diameter, speed, c: Contact):
    """The duration (s) of an elastic Hertz impact of a sphere on the wall at normal speed
    `speed`: 2.87 (m^2 / (r E*^2 v))^(1/5) (arrays broadcast)."""
    r = np.asarray(diameter, dtype=float) / 2.0
    m = 4.0 / 3.0 * math.pi * c.density * r ** 3
    v = np.maximum(np.asarray(speed, dtype=float), 1e-9)
    return 2.87 * (m * m / (r * c.effective_modulus ** 2 * v)) ** 0.2


def time_step(diameters: np.ndarray, fastest: float, c: Contact,
              samples: float = SAMPLES_PER_CONTACT) -> tuple[float, int]:
    """The time step (s) and the contacts' sampling interval (steps), `samples` in the
    fastest impact's contact: the module's text."""
    small = float(np.min(diameters))
    contact = float(hertz_time(small, fastest, c))
    dt = min(RAYLEIGH_FRACTION * rayleigh_time(small, c), contact / STEPS_PER_CONTACT)
    return dt, max(1, int(contact / dt / samples))


def _number(x: float) -> str:
    return f"{x:.10g}"


def _unflushed(dump: str) -> list[str]:
    """A dump's lines written to the file as its buffer fills, not at every frame: LIGGGHTS
    flushes each frame by default, a write to the file every sample, much of the cost of a
    feeder's sparse contacts (docs/dem.md, what it costs). It writes the rest when it exits,
    stopped by a signal too (engine.py), and the outputs are read only then."""
    return [f"dump_modify {dump} flush no"]


def _contacts_dumps(chute: Chute, entry: Entry, diameters: np.ndarray, dumps: dict, *,
                    dt: float, near: float, slowest: float) -> list[str]:
    """The contacts' dumps (name: (file, every so many steps)), each the grains the module's
    text says: near a wall, and moving along its normal or pressed on by it.

    A grain is written while near the plate (its gap below `near`, so that the last sample
    before a contact is in flight) and moving along the normal faster than `slowest`
    relative to it: a grain at rest or rolling on the plate is not written (the plate where
    it is: a vibrating plate's stroke times sin(2 pi f t)); a feeder's the same near a side
    wall, across the chute (the stroke moves the sides along themselves). One atom-style
    formula, as few nodes as it takes: LIGGGHTS parses it at every sample and evaluates
    each node grain by grain, the dump's cost on a feeder (docs/dem.md, what it costs):
    the radius is the grain's own `r`, the plate's motion numbers in it (an equal-style
    variable named in it is parsed again wherever it is named), and where along the chute
    a grain may touch a wall a threshold of the dump on x (a comparison, no formula),
    covering the plate's ends wherever its stroke carries them."""
    biggest = float(np.max(diameters))
    L, half = chute.chute_length, entry.width / 2.0
    top, speed = f"{_number(near)}", "vz"
    # the farthest a grain touching the plate is from it along x: its radius and the stroke
    reach = (abs(chute.stroke[0]) if chute.amplitude else 0.0) + biggest / 2.0
    if chute.amplitude:
        # the phase 2 pi f t as one number times the step, to all its digits (each token
        # is parsed at every sample)
        phase = f"step*{2 * math.pi * chute.frequency * float(_number(dt)):.17g}"
        sz = chute.stroke[1]
        top += f"+{_number(sz)}*sin({phase})"
        speed += f"-{_number(sz * 2 * math.pi * chute.frequency)}*cos({phase})"
    # ... or pressed on by more than PRESSED times its weight: the turn of an impact, its
    # normal speed passing zero, whose one sample in contact may fall there
    pressed = f"{_number(PRESSED * 9.81)}*mass"
    written = (f"(z-r<{top})*((abs({speed})>{_number(slowest)})"
               f"+(f_force_walls[3]>{pressed}))")
    columns = CONTACT_COLUMNS
    if chute.amplitude:
        # a feeder's one dump for the plate and the side walls (a dump evaluates its
        # formula for every grain at every sample, most of them written by none: one set)
        written += (f"+(abs(y)+r>{_number(half - near)})"
                    f"*((abs(vy)>{_number(slowest)})+(abs(f_force_walls[2])>{pressed}))")
        columns = FEEDER_COLUMNS
    lines = [f"variable written atom {written}"]
    for name, (path, every) in dumps.items():
        lines += [f"dump {name} all custom {every} {path} " + " ".join(columns),
                  f"dump_modify {name} thresh v_written > 0 "
                  f"thresh x > {_number(chute.start(biggest) - reach)} "
                  f"thresh x < {_number(L + reach)}"]
        lines += [f'dump_modify {name} format "{FEEDER_FORMAT}"'] if chute.amplitude else []
        lines += _unflushed(name)
    return lines


def box_top(entry: Entry, diameters: np.ndarray) -> float:
    """The box's height above the plate (m): the highest drop, ten grains and 2 cm more (a
    feeder's side walls are as high)."""
    return float(np.max(entry.position[:, 2])) + 10.0 * float(np.max(diameters)) + 0.02


def write_input(chute: Chute, entry: Entry, diameters: np.ndarray, c: Contact, *, dt: float,
                sample_every: int, t_end: float, exit_every: int, progress_every: int,
                near: float, slowest: float, contacts: bool = True,
                reference_every: int | None = None,
                restart: tuple | None = None, law: str = LAW,
                law_properties: tuple[str, ...] = ()) -> tuple[str, int]:
    """The LIGGGHTS input (the module's text) and its number of steps. The grains enter
    in the order given (grain i is LIGGGHTS' atom i + 1), each at its entry time; the run
    stops once every grain has left the box (past the chute's end or off its sides) or at
    t_end. contacts=False: without the contacts' output (what it costs: bench_dem.sh).
    reference_every: the same grains written every that many steps too, into REFERENCE
    (the dense reference the sampling is checked against: contacts.compare_impacts).
    restart (file, step, created): the input that resumes a run LIGGGHTS stopped at `step`,
    writing the restart `file`, with `created` grains in: the scene read from it (the
    grains, their contact histories with the wall), the outputs appended to, the grains
    not yet in and the steps left. law: the contact law's words (LAW: the module's text),
    law_properties: what else it reads, each `NAME STYLE VALUES` of a property/global fix
    (e.g. `characteristicVelocity scalar 0.2` for `hooke`)."""
    n = len(diameters)
    biggest = float(np.max(diameters))
    L, half = chute.chute_length, entry.width / 2.0
    top = box_top(entry, diameters)
    steps = int(math.ceil(t_end / dt))
    gx, gy, gz = chute.gravity_vector
    lines = [
        "# written by tribo dem (python/tribo/dem/script.py): the reference chute in the",
        "# plate's frame, gravity tilted; grains as the feed drew them",
        "atom_style granular", "atom_modify map array", "boundary f f f", "newton off",
        "communicate single vel yes", "units si", "hard_particles yes",
        f"region box block {_number(min(-5 * biggest, chute.start(biggest) - biggest))} "
        f"{_number(L + 0.01)} "
        f"{_number(-half - 5 * biggest)} {_number(half + 5 * biggest)} "
        f"{_number(-0.01)} {_number(top)} units box",
        "create_box 2 box",
    ] if restart is None else [
        "# resumed by tribo dem from the restart file LIGGGHTS wrote when it was stopped",
        f"read_restart {restart[0]}",
        # what a restart file does not hold
        "communicate single vel yes", "hard_particles yes", "newton off",
    ]
    lines += [
        f"neighbor {_number(0.5 * biggest)} bin", "neigh_modify delay 0",
        # type 1: the grains, type 2: the wall
        f"fix m1 all property/global youngsModulus peratomtype {_number(c.youngs_particle)} "
        f"{_number(c.youngs_wall)}",
        f"fix m2 all property/global poissonsRatio peratomtype {_number(c.poisson_particle)} "
        f"{_number(c.poisson_wall)}",
        f"fix m3 all property/global coefficientRestitution peratomtypepair 2 "
        + " ".join([_number(c.restitution)] * 4),
        f"fix m4 all property/global coefficientFriction peratomtypepair 2 "
        + " ".join([_number(c.friction)] * 4),
        f"fix m5 all property/global coefficientRollingFriction peratomtypepair 2 "
        + " ".join([_number(c.rolling_friction)] * 4),
        *[f"fix law{i} all property/global {p}" for i, p in enumerate(law_properties)],
        f"pair_style gran model {law}",
        "pair_coeff * *",
        f"timestep {_number(dt)}",
        f"fix gravity all gravity 9.81 vector {_number(gx)} {_number(gy)} {_number(gz)}",
        f"fix plate all mesh/surface file {PLATE} type 2",
    ]
    # a feeder (a vibrating chute) has side walls, moving with its plate along the stroke
    meshes = ("plate", "sides") if chute.amplitude else ("plate",)
    if chute.amplitude:
        (sx, sz), period = chute.stroke, _number(1.0 / chute.frequency)
        lines += [f"fix sides all mesh/surface file {SIDES} type 2"]
        lines += [f"fix vibrate_{mesh} all move/mesh mesh {mesh} wiggle amplitude "
                  f"{_number(sx)} 0 {_number(sz)} period {period}" for mesh in meshes]
    # one wall fix for every mesh (LIGGGHTS takes no second): its force is the sum of the
    # plate's and the sides' on a grain (contacts.py tells them apart by the grain's gap)
    lines += [
        f"fix walls all wall/gran model {law} "
        f"mesh n_meshes {len(meshes)} meshes {' '.join(meshes)} store_force yes",

        "fix integrate all nve/sphere",
        # the grains that leave the box (past the end, off the sides) are dropped
        "thermo_style custom step atoms", f"thermo {progress_every}",
        "thermo_modify lost ignore norm no",
        f"dump exits all custom {exit_every} {EXITS} " + " ".join(EXIT_COLUMNS),
        f"dump_modify exits thresh x > {_number(L)}",
    ] + _unflushed("exits")
    append = [] if restart is None else ["dump_modify exits append yes"]
    if contacts:
        dumps = {"contacts": (CONTACTS, sample_every)}
        if reference_every:
            dumps["reference"] = (REFERENCE, reference_every)
        lines += _contacts_dumps(chute, entry, diameters, dumps, dt=dt, near=near,
                                 slowest=slowest)
        append += [] if restart is None else [f"dump_modify {d} append yes" for d in dumps]
    lines += append
    # each grain enters at its step: a `run` to it, then the grain
    start = np.rint(entry.time / dt).astype(np.int64)
    done, first = (0, 0) if restart is None else (int(restart[1]), int(restart[2]))
    for i in range(first, n):
        if start[i] > done:
            lines.append(f"run {int(start[i] - done)}")
            done = int(start[i])
        (x, y, z), (vx, vy, vz) = entry.position[i], entry.velocity[i]
        lines += [f"create_atoms 1 single {_number(x)} {_number(y)} {_number(z)} units box",
                  f"set atom {i + 1} diameter {_number(diameters[i])} density {_number(c.density)} "
                  f"vx {_number(vx)} vy {_number(vy)} vz {_number(vz)}"]
    # then in pieces until the box is empty or the horizon is reached
    piece = max(progress_every, 1)
    remaining = max(steps - done, 0)
    pieces = int(math.ceil(remaining / piece))
    lines += ["variable left equal atoms", f"variable piece loop {max(pieces, 1)}",
              "label pieces", f"run {piece} post no",
              'if "${left} == 0" then "jump SELF finished"',
              "next piece", "jump SELF pieces", "label finished"]
    return "\n".join(lines) + "\n", done + pieces * piece
