"""A population's grains moved by a DEM engine, LIGGGHTS, through a device, each grain-wall
impact charged by the project's impact map (docs/dem.md): device.py (the chute, where the
grains enter), script.py (the LIGGGHTS input), engine.py (LIGGGHTS as a process),
contacts.py (the impacts and exits from its output), charging.py (the maps, the charge
carried), runner.py (the job into a folder, written as a population's)."""

from .device import Chute, DeviceError
from .runner import DemError, DemJob, DemReport

__all__ = ["Chute", "DemError", "DemJob", "DemReport", "DeviceError"]
