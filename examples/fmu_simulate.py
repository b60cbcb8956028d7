"""Drive a tribo FMU step by step with fmpy, as a co-simulation importer does: the
paper's drop, pushed along the plate for a while through the external-force input,
with the friction coefficient (a tunable parameter) raised halfway.

    .venv/bin/python examples/fmu_simulate.py [--fmu build/fmu/tribo_fmi2.fmu] [--stop 40]

Works with either FMU (FMI 2.0 or 3.0); prints a few outputs along the way.
"""

import argparse
import os
import shutil

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUTPUTS = ["X", "Y", "in_contact", "Q_static", "Q_sliding", "work_external"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fmu", default=os.path.join(ROOT, "build", "fmu", "tribo_fmi3.fmu"))
    parser.add_argument("--stop", type=float, default=40.0)
    parser.add_argument("--step", type=float, default=0.5)
    parser.add_argument("--epsilon", type=float, default=0.3)
    args = parser.parse_args()

    md = read_model_description(args.fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    fmi2 = md.fmiVersion == "2.0"
    unzipdir = extract(args.fmu)
    cls = FMU2Slave if fmi2 else FMU3Slave
    fmu = cls(guid=md.guid, unzipDirectory=unzipdir,
              modelIdentifier=md.coSimulation.modelIdentifier, instanceName="drop")
    set_real = fmu.setReal if fmi2 else fmu.setFloat64
    get_real = fmu.getReal if fmi2 else fmu.getFloat64

    fmu.instantiate()
    set_real([vr["epsilon"]], [args.epsilon])
    if fmi2:
        fmu.setInteger([vr["n_segments"]], [500])
        fmu.setupExperiment(startTime=0.0, stopTime=args.stop)
        fmu.enterInitializationMode()
    else:
        fmu.setUInt64([vr["n_segments"]], [500])  # a structural parameter in FMI 3.0
        fmu.enterInitializationMode(startTime=0.0, stopTime=args.stop)
    fmu.exitInitializationMode()

    print(f"{'t':>6} " + " ".join(f"{name:>14}" for name in OUTPUTS))
    n_steps = round(args.stop / args.step)
    for k in range(n_steps):
        t = k * args.step
        # inputs and tunables set between steps hold from this communication point on
        set_real([vr["F_T_ext"]], [5e-4 if 10.0 <= t < 20.0 else 0.0])
        if k == n_steps // 2:
            set_real([vr["mu"]], [1.0])
        fmu.doStep(currentCommunicationPoint=t, communicationStepSize=args.step)
        if (k + 1) % max(1, n_steps // 16) == 0:
            values = get_real([vr[name] for name in OUTPUTS])
            print(f"{t + args.step:6.1f} " + " ".join(f"{v:14.6g}" for v in values))

    fmu.terminate()
    fmu.freeInstance()
    shutil.rmtree(unzipdir, ignore_errors=True)


if __name__ == "__main__":
    main()
