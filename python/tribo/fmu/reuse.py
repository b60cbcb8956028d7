"""FMU instances kept from one run to the next within a task (`Instances`): a Dask task's
runs, a serial sweep's, one after another in one thread.

A run that made its own instance and freed it again spent, besides the core's work, the
instance's making (fmpy's object, the logger's callbacks, fmi3InstantiateCoSimulation /
fmi2Instantiate) and freeing. A kept instance is reset instead (fmi3Reset / fmi2Reset: the
tribo FMUs free their core and restore every start value, fmu/lifecycle.c's
fmu_restore_start_values, the function instantiation itself ends with), so that the next
run starts from the state a new instance has: its numbers are a new instance's to the bit
(tests/python/test_reuse.py, FMI 2.0 and 3.0). The executor makes one `Instances` per task
and closes it when the task ends; nothing is kept between tasks or shared between threads.
"""

import contextlib

from .image import FmuImage
from .instance import Instance


class Instances:
    """The FMU instances the runs of one task share: one per (FMU, instance name), made on
    first use and handed out again, reset, to the next run that asks. An instance whose run
    raised is freed, not handed out again: a reset is not known to restore every state a
    failure leaves. `close` frees them all."""

    def __init__(self):
        self._kept = {}  # (the FMU's sha256, instance name) -> Instance, between two runs

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    @contextlib.contextmanager
    def use(self, image: FmuImage, name: str):
        """An instance of `image` for one run, in the state a new one has (its log empty)."""
        instance = self._kept.pop((image.sha256, name), None)
        if instance is None:
            instance = Instance(image, name=name)
        else:
            instance.reset()
        try:
            yield instance
        except BaseException:
            instance.free()
            raise
        self._kept[(image.sha256, name)] = instance

    def close(self) -> None:
        kept, self._kept = self._kept, {}
        for instance in kept.values():
            instance.free()


@contextlib.contextmanager
def instance_for(image: FmuImage, name: str, instances: Instances | None = None):
    """An instance for one run: `instances`' (kept for the task's next run), or, without
    them, a new one freed after the run."""
    if instances is not None:
        with instances.use(image, name) as instance:
            yield instance
        return
    instance = Instance(image, name=name)
    try:
        yield instance
    finally:
        instance.free()


def shares_instances(function):
    """Marks a run function `function(image, spec, instances=None)` whose runs, one after
    another, may share FMU instances: the executors pass it each task's `Instances`
    (batch/executors.py); called as any run function, `function(image, spec)`, each run
    makes its own."""
    function.shares_instances = True
    return function


def runs_share_instances(function) -> bool:
    return getattr(function, "shares_instances", False) is True
