"""tribo grain: one grain down the chute through the SI FMU, its q/m at the end: what
tribo.run_si gives from Python, from the command line, in one line per result.

    tribo grain --particle PE --wall steel --size 1e-3 --epsilon 0.6
    tribo grain --particle nylon --size 5e-4 --epsilon 1 --chute-length 0.5 --tilt-deg 35
    tribo grain --size 2e-3 --set mu=0.5 --materials out/calibration/materials.toml

The grain is a population's grain of the values given (tribo population --help: the same
parameters, its run to the chute's exit or the horizon --t-end, the same checks): its
size is the long diameter 2a in m, angles in degrees, omega0 in rad/s, drop_height in m,
drop_speed in m/s. It prints how the run ended (left the chute, at rest on it, or still
on it at the horizon), the exit's time and speed, the impacts, and each charge model's
charge (C, of the spheroid of semi-axes a, b, b: docs/si.md) and q/m (C/kg, with µC/kg
beside it). Nothing is written; a mistake is one line.
"""

from ..populations.feed_variables import DEFAULT_CHUTE, FEED_UNITS, FEED_VARIABLES
from .common import INPUT_ERRORS, add_materials_option, fail, feed_of, name_value, one_line

# the grain's values where not given: the reference case's drop (feed_variables.py) of a
# 1 mm grain of roundness 0.6 lying flat
GRAIN_DEFAULTS = {"epsilon": 0.6, "size": 1e-3, "phi0_deg": 0.0, "omega0": 0.0,
                  "drop_height": 0.01, "drop_speed": 0.0, "drop_angle_deg": 0.0}
# what each is (populations/feed.py's text), before its unit (FEED_UNITS)
MEANINGS = {"epsilon": "roundness", "size": "size,", "phi0_deg": "orientation of the long axis at "
            "the drop,", "omega0": "spin at the drop,", "drop_height": "height of the lowest "
            "point above the chute,", "drop_speed": "speed at the drop,",
            "drop_angle_deg": "direction of the drop speed,"}


def add_arguments(p) -> None:
    p.add_argument("--particle", default="PE", help="particle material (default PE)")
    p.add_argument("--wall", default="steel", help="wall material (default steel)")
    for name in FEED_VARIABLES:
        p.add_argument(f"--{name.replace('_', '-')}", dest=name, type=float,
                       default=GRAIN_DEFAULTS[name],
                       help=f"{MEANINGS[name]} {FEED_UNITS[name]} (default "
                            f"{GRAIN_DEFAULTS[name]:g})")
    p.add_argument("--chute-length", type=float, default=DEFAULT_CHUTE["chute_length"],
                   help=f"length of the chute, m (default {DEFAULT_CHUTE['chute_length']:g})")
    p.add_argument("--tilt-deg", type=float, default=DEFAULT_CHUTE["tilt_deg"],
                   help=f"tilt of the chute from the horizontal, degrees (default "
                        f"{DEFAULT_CHUTE['tilt_deg']:g})")
    p.add_argument("--set", type=name_value, action="append", default=[], metavar="NAME=VALUE",
                   help="any other SI parameter by the package's names (mu=0.5, "
                        "charging_time=1e-3, ...)")
    p.add_argument("--t-end", type=float, default=5.0, help="the horizon, s (default 5)")
    add_materials_option(p)
    p.add_argument("--fmu", help="the SI FMU (default: tribo_si_fmi3.fmu of the build)")


def run(args) -> int:
    try:
        lines = grain_lines(args)
    except INPUT_ERRORS as e:
        return fail(args.prog, one_line(e))
    except RuntimeError as e:  # the FMU failed in the run: one line, exit 1
        return fail(args.prog, one_line(e), 1)
    for line in lines:
        print(line)
    return 0


def grain_lines(args) -> list[str]:
    """The grain's run (a population of one, populations/runner.py's checks) and its lines."""
    # the job's modules (and numpy, pandas, fmpy) once it runs: --help and a mistake in the
    # options need none of them (common.py)
    from ..fmu import FmuImage
    from ..fmu.charge_models import charge_models  # the same
    from ..fmu.locate import find_fmu  # the same
    from ..fmu.names import format_number  # the same
    from ..populations.feed import run_particle  # the same
    from ..populations.runner import prepare_population  # the same
    image = FmuImage.load(find_fmu(args.fmu, "si"))
    feed = feed_of(args)
    spec = prepare_population(feed, 1, 0, args.t_end, image)[0]
    row = run_particle(image, spec).row
    p = spec.params
    what = (f"grain: {feed.describe()['particle']} on {feed.describe()['wall']}, size "
            f"{format_number(p['size'])} m, epsilon {format_number(p['epsilon'])}, on "
            f"{format_number(p['chute_length'])} m tilted {format_number(p['tilt_deg'])}°")
    if row["exited"]:
        end = (f"left the chute at {row['exit_time']:.4g} s at {row['exit_speed']:.4g} m/s "
               f"after {row['impacts']} impact(s)")
    elif row.get("end_reason") == 3:
        end = f"came to rest on the chute at {row['rest_time']:.4g} s"
    else:
        end = f"was still on the chute at the horizon of {format_number(args.t_end)} s"
    lines = [f"{what}: {end}"]
    for model in charge_models(image.model_description()):
        q, qm = row[f"charge_{model}"], row[f"charge_to_mass_{model}"]
        lines.append(f"grain: {model} model: q = {q:.4g} C, q/m = {qm:.4g} C/kg "
                     f"({qm * 1e6:.4g} µC/kg)")
    return lines
