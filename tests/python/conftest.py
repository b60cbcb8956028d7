"""Fixtures of the FMU tests.

The FMUs and the test tools come from the build directory: build/ by default, or the
one named by the environment variable TRIBO_BUILD_DIR (e.g. build-fmu). Build first
(scripts/setup.sh, or cmake --build <dir>); the tests fail, not skip, without them.
"""

import os
import sys
import zipfile

import pytest
from fmpy import read_model_description

from tribo_fmu import BUILD_DIR


@pytest.fixture(autouse=True)
def no_figure_left_open():
    """Figures a test keeps to look at (a stubbed save) are closed after it, so that a
    worker's tests do not pile them up in pyplot (matplotlib warns past 20)."""
    yield
    if "matplotlib.pyplot" in sys.modules:  # only where a test drew one
        sys.modules["matplotlib.pyplot"].close("all")


def built(*parts):
    path = os.path.join(BUILD_DIR, *parts)
    if not os.path.exists(path):
        pytest.fail(f"{path} is missing: build first (scripts/setup.sh or cmake --build), "
                    f"or point TRIBO_BUILD_DIR at the build directory")
    return path


@pytest.fixture(scope="session")
def fmu_file():
    """The .fmu of an FMI version; prefix "tribo" (dimensionless) or "tribo_si" (SI)."""
    return lambda version, prefix="tribo": built("fmu", f"{prefix}_fmi{version}.fmu")


@pytest.fixture(scope="session")
def fmu_dir(tmp_path_factory):
    """The unpacked FMU of an FMI version (unpacked once per session); prefix as for
    fmu_file."""
    dirs = {}

    def unpack(version, prefix="tribo"):
        key = (prefix, version)
        if key not in dirs:
            target = tmp_path_factory.mktemp(f"{prefix}_fmi{version}")
            with zipfile.ZipFile(built("fmu", f"{prefix}_fmi{version}.fmu")) as z:
                z.extractall(target)
            dirs[key] = str(target)
        return dirs[key]

    return unpack


@pytest.fixture(scope="session")
def reference_exe():
    return built("fmu", "tribo_reference_run")


@pytest.fixture(scope="session")
def output_names(fmu_dir):
    """The scalar outputs, in the order of the modelDescription."""
    md = read_model_description(fmu_dir(2), validate=False)
    return [v.name for v in md.modelVariables if v.causality == "output"]
