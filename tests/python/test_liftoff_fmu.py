"""run_end = first_liftoff through the FMUs: the step ends at the lift-off (Discard and
terminate, as at the chute's exit), lifted_off is set, and a state saved there restores."""

import pytest
from fmpy.fmi1 import FMICallException

import tribo
from tribo.fmu import FmuImage, Instance, unpacked


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("integrator", [0, 1])
def test_a_state_saved_at_the_liftoff_restores(version, integrator):
    with unpacked(FmuImage.load(tribo.find_fmu(version))) as fmu_dir:
        i = Instance(fmu_dir)
        try:
            i.set_parameters({"run_end": 1, "integrator": integrator, "drop_speed": 0.5,
                              "dt": 1e-3, "n_segments": 64})
            i.init(0.0)
            assert not i.step_to(40.0) and 0.0 < i.t < 40.0
            assert i.get("lifted_off") and not i.get("exited") and not i.get("in_contact")
            state = i.get_state()
            data = i.serialize(state)
            i.free_state(state)
            i.set_state(i.deserialize(data))  # was refused: "its run is not over"
            assert i.get("lifted_off") and i.get("time") == i.t
            with pytest.raises(FMICallException):  # a further step: the run is over
                i.step_to(i.t + 1.0)
            assert "the particle lifted off the plate" in i.errors()[-1]
        finally:
            i.free()
