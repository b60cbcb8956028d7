"""Where the FMUs are: a path given, or the build directory, $TRIBO_BUILD_DIR or the
checkout's build/ (the package installed in editable mode sits in <checkout>/python/)."""

import os

PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))
CHECKOUT = os.path.dirname(os.path.dirname(PACKAGE_DIR))
FMU_NAMES = {2: "tribo_fmi2.fmu", 3: "tribo_fmi3.fmu"}
SI_FMU_NAMES = {2: "tribo_si_fmi2.fmu", 3: "tribo_si_fmi3.fmu"}


def build_dir() -> str:
    return os.path.abspath(os.environ.get("TRIBO_BUILD_DIR", os.path.join(CHECKOUT, "build")))


def find_fmu(fmu: str | int | None = None, si: bool = False) -> str:
    """The path of an FMU: `fmu` itself if it is a path, else the FMI 2.0 (2) or 3.0 (3,
    the default) FMU of the build directory, the dimensionless one or (si) the SI one.
    FileNotFoundError, saying what to do, if it is not there."""
    if isinstance(fmu, str):
        path = fmu
    else:
        names = SI_FMU_NAMES if si else FMU_NAMES
        path = os.path.join(build_dir(), "fmu", names[3 if fmu is None else fmu])
    if not os.path.isfile(path):
        raise FileNotFoundError(f"{path} not found: build the FMUs (scripts/setup.sh), set "
                                f"TRIBO_BUILD_DIR to the build directory, or give the FMU's path")
    return path
