"""Where the FMUs are: a path given, or the build directory, $TRIBO_BUILD_DIR or the
checkout's build/ (the package installed in editable mode sits in <checkout>/python/)."""

import os

PACKAGE_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # tribo/, above fmu/
CHECKOUT = os.path.dirname(os.path.dirname(PACKAGE_DIR))
# the FMUs' modelIdentifiers by variant: the dimensionless model, or the SI front end
# (physical units, docs/model.md section 8), or the free-fall separator (docs/separator.md)
VARIANTS = {"dimensionless": "tribo", "si": "tribo_si", "separator": "tribo_separator"}


def build_dir() -> str:
    return os.path.abspath(os.environ.get("TRIBO_BUILD_DIR", os.path.join(CHECKOUT, "build")))


def find_fmu(fmu: str | int | None = None, variant: str = "dimensionless", si: bool = False) -> str:
    """The path of an FMU: `fmu` itself if it is a path, else the FMI 2.0 (2) or 3.0 (3,
    the default) FMU of the build directory, of the variant "dimensionless" (tribo_fmi<v>),
    "si" (tribo_si_fmi<v>; si=True says the same) or "separator" (tribo_separator_fmi<v>). FileNotFoundError, saying what to do,
    if it is not there."""
    variant = "si" if si else variant
    if isinstance(fmu, str):
        path = fmu
    else:
        if variant not in VARIANTS:
            raise ValueError(f"variant {variant!r}: one of {', '.join(VARIANTS)}")
        name = f"{VARIANTS[variant]}_fmi{3 if fmu is None else fmu}.fmu"
        path = os.path.join(build_dir(), "fmu", name)
    if not os.path.isfile(path):
        raise FileNotFoundError(f"{path} not found: build the FMUs (scripts/setup.sh), set "
                                f"TRIBO_BUILD_DIR to the build directory, or give the FMU's path")
    return path
