"""The vibrating chute's report (docs/feeder.md): conveying speed, impacts and charge.

    .venv/bin/python examples/feeder.py [--out docs] [--grains 40] [--workers 2]

Writes into <out>:
    feeder_speed.csv / feeder_speed.png     a 1 mm PE grain's conveying speed on a level
                                            feeder at 50 Hz against the throw number K
                                            (psi_v 30 degrees) and against the stroke angle
                                            psi_v (K = 2.5), beside the point-mass theory
    feeder_length.csv / feeder_length.png   the reference feed through feeders of 0.1 to
                                            1 m (50 Hz, 0.5 mm, psi_v 30 degrees, level):
                                            impacts per grain and the exit stream's q/m,
                                            beside the still chute's (tilted 30 degrees)
and prints the tables docs/feeder.md shows.

The point-mass theory (the model of vibratory conveying that Sloot & Kruyt, Powder Technol.
87 (1996) 203, set against their measurements, after Booth & McCallion and Gaberson): a point
mass on the plate, at rest with it, sliding on it with Coulomb friction mu, or in flight,
landing without rebound (a perfectly inelastic impact keeps the velocity along the plate).
It is integrated here in the plate's frame, the same inertial force as the model's
(docs/model.md section 9b), with 4000 steps a cycle over 60 cycles, the mean speed over the
last 40.
"""

import argparse
import math
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

import tribo  # noqa: E402

G = 9.81
FREQUENCY = 50.0
OMEGA = 2.0 * math.pi * FREQUENCY
MU = 0.3  # the SI FMU's default friction, the one the grain runs with


def amplitude_for(K: float, psi_deg: float) -> float:
    """The stroke's amplitude (m) at 50 Hz that gives the throw number K on a level chute."""
    return K * G / (OMEGA ** 2 * math.sin(math.radians(psi_deg)))


def point_mass_speed(K: float, psi_deg: float, mu: float = MU, cycles: int = 60,
                     steps: int = 4000) -> float:
    """The point-mass theory's mean conveying speed on a level plate, in units of A omega
    cos(psi): rest, slide and flight, landing without rebound."""
    psi = math.radians(psi_deg)
    A = amplitude_for(K, psi_deg)
    dt = 2.0 * math.pi / OMEGA / steps
    u = v = y = 0.0  # velocity along and normal to the plate, height, relative to the plate
    travelled = 0.0
    counted = 0
    for k in range(cycles * steps):
        t = k * dt
        f = A * OMEGA ** 2 * math.sin(OMEGA * t)  # the inertial force per unit mass
        f_t, f_n = f * math.cos(psi), f * math.sin(psi) - G
        if y > 0.0 or v > 0.0 or f_n > 0.0:  # in flight
            u += f_t * dt
            v += f_n * dt
            y += v * dt
            if y <= 0.0:  # lands: no rebound
                y = v = 0.0
        else:  # on the plate, pressed by N = -f_n
            N = -f_n
            if u == 0.0 and abs(f_t) <= mu * N:
                pass  # at rest with the plate
            else:
                direction = math.copysign(1.0, u) if u != 0.0 else math.copysign(1.0, f_t)
                u_new = u + (f_t - mu * N * direction) * dt
                u = 0.0 if u != 0.0 and u_new * u < 0.0 else u_new
        if k >= (cycles - 40) * steps:
            travelled += u * dt
            counted += 1
    return travelled / (counted * dt) / (A * OMEGA * math.cos(psi))


def grain_speed(K: float, psi_deg: float, length: float = 0.2, phases: int = 5) -> dict:
    """A 1 mm PE grain (epsilon 0.6) dropped from 1 mm onto a level feeder at `phases` phases
    of the stroke: its mean speed over `length` (m/s, and in units of A omega cos(psi)) and
    impacts, the mean over the phases (a bouncing grain's path is chaotic: the phases'
    spread, min to max, is given too)."""
    A = amplitude_for(K, psi_deg)
    speeds, impacts = [], []
    for k in range(phases):
        end = tribo.run_si("PE", "steel", size=1e-3, epsilon=0.6, chute_length=length,
                           tilt_deg=0.0, drop_height=1e-3, vibration_amplitude=A,
                           vibration_frequency=FREQUENCY, vibration_angle_deg=psi_deg,
                           vibration_phase_deg=360.0 * k / phases, t_end=60.0,
                           record_interval=None).iloc[-1]
        speeds.append(length / end["exit_time"] if end["exited"] == 1 else 0.0)
        impacts.append(float(end["impacts"]))
    scale = A * OMEGA * math.cos(math.radians(psi_deg))
    return {"K": K, "psi_deg": psi_deg, "amplitude_mm": 1e3 * A, "speed": float(np.mean(speeds)),
            "speed_ratio": float(np.mean(speeds)) / scale,
            "ratio_min": min(speeds) / scale, "ratio_max": max(speeds) / scale,
            "impacts": float(np.mean(impacts)), "point_mass_ratio": point_mass_speed(K, psi_deg)}


def stream(length: float, grains: int, workers: int, vibrating: bool) -> dict:
    """The reference feed (tribo population's defaults) through a feeder of `length` m at 50 Hz,
    0.5 mm, psi_v 30 degrees, level, or down the still chute tilted 30 degrees."""
    chute = {"chute_length": length, "tilt_deg": 0.0 if vibrating else 30.0}
    if vibrating:
        chute.update(vibration_amplitude=5e-4, vibration_frequency=FREQUENCY,
                     vibration_angle_deg=30.0)
    with tempfile.TemporaryDirectory() as out:
        report = tribo.population(grains, seed=1, chute=chute, t_end=120.0, out=out,
                                  processes=workers > 1, workers=workers, serial=workers == 1)
    rows, summary = report.results, report.summary
    everyone = summary[(summary["grouping"] == "all") & (summary["model"] == "static")].iloc[0]
    return {"device": "feeder" if vibrating else "still chute", "length_m": length,
            "grains": len(rows), "left": int((rows["exited"] == 1).sum()),
            "impacts_median": float(rows["impacts"].median()),
            "qm_stream_uC_per_kg": 1e6 * float(everyone["stream_mean"]),
            "cpu_s_per_grain": float(rows["cpu_s"].mean())}


def markdown(table: pd.DataFrame) -> str:
    """The table in markdown, numbers to 3 significant digits."""
    cell = lambda v: f"{v:.3g}" if isinstance(v, float) else str(v)  # noqa: E731
    lines = ["| " + " | ".join(table.columns) + " |", "|" + "---|" * len(table.columns)]
    lines += ["| " + " | ".join(cell(v) for v in row) + " |" for row in table.itertuples(index=False)]
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="docs")
    parser.add_argument("--grains", type=int, default=40)
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    for name in ("grains", "workers"):
        if getattr(args, name) < 1:
            parser.error(f"--{name} {getattr(args, name)} is outside its range: at least 1")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    speeds = pd.DataFrame([grain_speed(K, 30.0) for K in (1.2, 1.6, 2.0, 2.5, 3.0, 4.0)] +
                          [grain_speed(2.5, psi) for psi in (15.0, 20.0, 45.0, 60.0)])
    speeds.to_csv(out / "feeder_speed.csv", index=False)
    print(markdown(speeds), flush=True)

    lengths = pd.DataFrame([stream(L, args.grains, args.workers, vibrating)
                            for vibrating in (True, False) for L in (0.1, 0.3, 0.5, 1.0)])
    lengths.to_csv(out / "feeder_length.csv", index=False)
    print(markdown(lengths), flush=True)

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    by_K = speeds[speeds["psi_deg"] == 30.0].sort_values("K")
    a.errorbar(by_K["K"], by_K["speed_ratio"],
               yerr=[by_K["speed_ratio"] - by_K["ratio_min"], by_K["ratio_max"] - by_K["speed_ratio"]],
               fmt="o-", capsize=3, label="1 mm PE grain (tribo; 5 phases, min to max)")
    a.plot(by_K["K"], by_K["point_mass_ratio"], "s--", label="point-mass theory")
    a.set_xlabel("throw number K (psi_v = 30 deg, 50 Hz, level)")
    a.set_ylabel("conveying speed / (A omega cos psi_v)")
    a.legend()
    by_psi = speeds[speeds["K"] == 2.5].sort_values("psi_deg")
    b.errorbar(by_psi["psi_deg"], by_psi["speed_ratio"],
               yerr=[by_psi["speed_ratio"] - by_psi["ratio_min"],
                     by_psi["ratio_max"] - by_psi["speed_ratio"]],
               fmt="o-", capsize=3, label="1 mm PE grain (tribo; 5 phases, min to max)")
    b.plot(by_psi["psi_deg"], by_psi["point_mass_ratio"], "s--", label="point-mass theory")
    b.set_xlabel("stroke angle psi_v, degrees (K = 2.5)")
    b.legend()
    fig.tight_layout()
    fig.savefig(out / "feeder_speed.png", dpi=120)

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    for device, style in (("feeder", "o-"), ("still chute", "s--")):
        part = lengths[lengths["device"] == device]
        a.plot(part["length_m"], part["impacts_median"], style, label=device)
        b.plot(part["length_m"], part["qm_stream_uC_per_kg"], style, label=device)
    a.set_xlabel("length, m")
    a.set_ylabel("impacts per grain (median)")
    b.set_xlabel("length, m")
    b.set_ylabel("stream q/m, uC/kg (static model)")
    a.legend()
    fig.tight_layout()
    fig.savefig(out / "feeder_length.png", dpi=120)


if __name__ == "__main__":
    main()
