"""line_flights: a line's flights through `line/grain.py`'s Flights (one separator instance
reset between a grain's flights, values set and read at once) against `fly` (an instance
per flight, values by name), on the same flights (docs/line.md, "Benchmark").

    TRIBO_BUILD_DIR=build .venv/bin/python bench/line_flights.py [GRAINS=100]

Runs GRAINS grains of the default line at 4 voltages once to record their flights, then
times each path over them (3 rounds, the process's CPU clock, the best round) and checks
that both give the same flights to the bit.
"""

import math
import sys
import time

import numpy as np

import tribo.line.grain as grain
from tribo.line.mixture import Line, line_specs


def same(a: dict, b: dict) -> bool:
    def bits(x):
        return np.float64(x).view(np.int64) if isinstance(x, float) else x
    return list(a) == list(b) and all(type(a[k]) is type(b[k]) and bits(a[k]) == bits(b[k])
                                      for k in a)


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100
    images = grain.load_images(3, 3, {}, np.linspace(5e3, 40e3, 4))
    specs = line_specs(Line(), n, 1, 10.0, images.models, images.chute.model_description())
    grains = []  # per grain: (parameter names, [(values, t_exit, inputs)])
    original = grain.Flights.fly

    def recorded(self, values, t_exit, inputs):
        if not grains or grains[-1][0] is not self:
            grains.append((self, list(self.parameters.names), []))
        grains[-1][2].append((list(values), t_exit, inputs))
        return original(self, values, t_exit, inputs)

    grain.Flights.fly = recorded
    try:
        for spec in specs:
            grain.run_line_grain(images, spec)
    finally:
        grain.Flights.fly = original
    flights = sum(len(g[2]) for g in grains)

    def through_fly():
        return [grain.fly(images.separator, dict(zip(names, values)), t_exit,
                          None if inputs is None else dict(zip(grain.INPUTS, inputs)))
                for _, names, runs in grains for values, t_exit, inputs in runs]

    def through_flights():
        out = []
        for _, names, runs in grains:
            with grain.Flights(images.separator, names) as f:
                out += [f.fly(values, t_exit, inputs) for values, t_exit, inputs in runs]
        return out

    for name, path in (("fly (an instance per flight, by name)", through_fly),
                       ("Flights (one instance a grain, at once)", through_flights)):
        best = math.inf
        for _ in range(3):
            t0 = time.process_time()
            got = path()
            best = min(best, time.process_time() - t0)
        print(f"{name}: {best / flights * 1e6:.1f} us a flight ({flights} flights)")
        if name.startswith("fly"):
            expected = got
        elif not all(same(a, b) for a, b in zip(got, expected)):
            sys.exit("the two paths' flights differ")
    print("the same flights to the bit")


if __name__ == "__main__":
    main()
