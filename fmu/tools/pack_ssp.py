"""Packs the separation line's SSP package (python/tribo/ssp.py, docs/separator.md "The SSP
package") from the FMI 2.0 FMUs of the build: the build's step after the FMUs.

    python pack_ssp.py --out build/ssp/tribo_line.ssp --chute build/fmu/tribo_si_fmi2.fmu \
        --separator build/fmu/tribo_separator_fmi2.fmu [--epoch 1700000000]

tribo/ssp.py is loaded by its path: the build needs the standard library only, not the
package's dependencies.
"""

import argparse
import importlib.util
import os

SSP_MODULE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python",
                          "tribo", "ssp.py")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", required=True)
    parser.add_argument("--chute", required=True, help="the SI chute's .fmu")
    parser.add_argument("--separator", required=True, help="the separator's .fmu")
    parser.add_argument("--epoch", type=int,
                        default=int(os.environ.get("SOURCE_DATE_EPOCH", "315532800")))
    args = parser.parse_args()
    spec = importlib.util.spec_from_file_location("tribo_ssp", SSP_MODULE)
    ssp = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ssp)
    ssp.build(args.out, args.chute, args.separator, epoch=args.epoch)


if __name__ == "__main__":
    main()
