"""The benchmark's data (scripts/bench_calibration.sh): 20 single impacts and 3 chute runs of
PE on steel made by the model at sigma0 = -1.5e-5 C/m2 (t0 = 0), each value off by a
normal 0.05 decades (seeded), written as the CSV files tribo calibrate takes into the
folder given."""

import os
import sys

import numpy as np
import pandas as pd

import tribo

SIGMA0, NOISE = -1.5e-5, 0.05
out = sys.argv[1]
rng = np.random.default_rng(1)
impacts = pd.DataFrame({"speed": rng.uniform(0.5, 5.0, 20), "angle_deg": rng.uniform(20, 90, 20),
                        "size": rng.choice([5e-4, 1e-3, 2e-3], 20),
                        "epsilon": rng.uniform(0.5, 1.0, 20), "phi0_deg": rng.uniform(0, 90, 20)})
impacts["charge"] = [tribo.single_impact("PE", "steel", settings={"sigma0": SIGMA0}, **row)["charge"]
                     * 10 ** rng.normal(0, NOISE) for row in impacts.to_dict("records")]
chutes = pd.DataFrame({"chute_length": [0.1, 0.2, 0.3], "tilt_deg": [30.0, 35.0, 40.0],
                       "grains": 50, "seed": [1, 2, 3]})
chutes["q_per_m"] = [tribo.chute_stream("PE", "steel", int(row["grains"]), seed=int(row["seed"]),
                                        chute={"chute_length": row["chute_length"],
                                               "tilt_deg": row["tilt_deg"]},
                                        settings={"sigma0": SIGMA0}, serial=True).statistics["q_per_m"]
                     * 10 ** rng.normal(0, NOISE) for row in chutes.to_dict("records")]
impacts.to_csv(os.path.join(out, "impacts.csv"), index=False)
chutes.to_csv(os.path.join(out, "chutes.csv"), index=False)
print(f"data: {len(impacts)} impacts, {len(chutes)} chute runs at sigma0 = {SIGMA0:g} C/m2, "
      f"{NOISE} decades of noise, in {out}")
