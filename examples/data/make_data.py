"""The example data of docs/calibration.md and of the commands' --help (`tribo calibrate
--impacts examples/data/impacts.csv --chutes examples/data/chutes.csv`, `tribo population
--measured examples/data/sieve.csv`): synthetic measurements, made by the model itself for
PE on steel at sigma0 = -1.5e-5 C/m2 with complete transfer, each value off by a normal
0.05 decades (about 12 %, a plausible scatter); a measured file takes their place row for
row. Run from the checkout's root to make them again: python examples/data/make_data.py"""

import os

import numpy as np
import pandas as pd

import tribo

HERE = os.path.dirname(os.path.abspath(__file__))
SIGMA0 = -1.5e-5
NOISE = 0.05  # decades


def impacts(rng) -> pd.DataFrame:
    rows = []
    for speed, angle_deg, size in [(1, 90, 1e-3), (2, 90, 1e-3), (4, 90, 1e-3), (2, 45, 2e-3),
                                   (3, 30, 2e-3), (5, 60, 5e-4)]:
        hit = tribo.single_impact("PE", "steel", speed=speed, angle_deg=angle_deg, size=size,
                                  epsilon=1.0, settings={"sigma0": SIGMA0})
        rows.append({"speed": speed, "angle_deg": angle_deg, "size": size, "epsilon": 1.0,
                     "charge": float(f"{hit['charge'] * 10 ** rng.normal(0, NOISE):.3g}")})
    return pd.DataFrame(rows)


def chutes(rng, out: str) -> pd.DataFrame:
    """Two short chutes, 10 grains of the default feed each (what the model draws for the
    row: its `grains`), the stream's mass-weighted q/m (a Faraday cup at the end)."""
    rows = []
    for length in (0.1, 0.2):
        pop = tribo.population(10, seed=0, chute={"chute_length": length, "tilt_deg": 30.0},
                               t_end=2.0, settings={"sigma0": SIGMA0}, serial=True,
                               out=os.path.join(out, f"chute-{length:g}"))
        stream = pop.summary.query("grouping == 'all' and model == 'static'")["stream_mean"].iloc[0]
        rows.append({"chute_length": length, "tilt_deg": 30.0,
                     "q_per_m": float(f"{stream * 10 ** rng.normal(0, NOISE):.3g}"),
                     "grains": 10, "t_end": 2.0})
    return pd.DataFrame(rows)


def sieve() -> pd.DataFrame:
    """A sieve analysis with roundness measured on the same grains: size (m) and epsilon."""
    return pd.DataFrame({"size": [4e-4, 6e-4, 8e-4, 1e-3, 1.2e-3, 1.5e-3],
                         "epsilon": [0.45, 0.55, 0.7, 0.8, 0.9, 0.95]})


if __name__ == "__main__":
    rng = np.random.default_rng(7)
    impacts(rng).to_csv(os.path.join(HERE, "impacts.csv"), index=False)
    chutes(rng, os.path.join("out", "example-data")).to_csv(os.path.join(HERE, "chutes.csv"),
                                                            index=False)
    sieve().to_csv(os.path.join(HERE, "sieve.csv"), index=False)
