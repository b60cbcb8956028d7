"""A population's feed as settings lines of the SI front end (bench/population_core.c): the
particles `tribo population -n N --seed S` draws for PE on steel (the reference case's feed),
one line per particle in the FMU's names and units.

    .venv/bin/python bench/population_feed.py N SEED [NAME=VALUE ...] > feed.txt

NAME=VALUE: a feed variable's distribution or number (e.g. epsilon=1 for discs) or any
other SI parameter (e.g. mu=0.5), by the package's names."""

import sys

from tribo.fmu import FmuImage
from tribo.fmu.locate import find_fmu
from tribo.fmu.names import to_fmu
from tribo.populations.feed import Feed, specs_of
from tribo.populations.feed_variables import FEED_VARIABLES


def main(argv):
    n, seed = int(argv[0]), int(argv[1])
    given = dict(a.split("=", 1) for a in argv[2:])
    feed = Feed("PE", "steel",
                distributions={k: v for k, v in given.items() if k in FEED_VARIABLES},
                settings={k: float(v) for k, v in given.items() if k not in FEED_VARIABLES})
    md = FmuImage.load(find_fmu(3, "si")).model_description()
    for spec in specs_of(feed, n, seed, 5.0):
        params = to_fmu(md, spec.params)
        params.pop("work_limit", None)  # the benchmark measures each grain to its end
        print(" ".join(f"{k}={float(v)!r}" for k, v in params.items()))


if __name__ == "__main__":
    main(sys.argv[1:])
