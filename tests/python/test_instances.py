"""Instances are independent of each other and of their history: interleaved runs,
reset-and-rerun cycles and 1000 instantiate / free cycles."""

import ctypes
import gc
import os
from ctypes import byref, c_char_p, create_string_buffer

import pytest

from tribo_fmu import INTEGRATORS, VERSIONS, Slave, integrator_id

SMALL = {"n_segments": 64}
TIMES = [0.25, 0.5, 0.75, 1.0]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", INTEGRATORS, ids=integrator_id)
def test_interleaved_instances_equal_each_run_alone(fmu_dir, output_names, version, integrator):
    scenes = [dict(SMALL, integrator=integrator), dict(SMALL, integrator=integrator, epsilon=0.3, mu=1.0)]
    alone = []
    for scene in scenes:
        s = Slave(fmu_dir(version), version).init(**scene)
        alone.append(s.run(TIMES, output_names))
        s.free()
    a, b = (Slave(fmu_dir(version), version, name=f"instance_{i}").init(**scene)
            for i, scene in enumerate(scenes))
    together = [[], []]
    for t in TIMES:
        for s, rows in zip((a, b), together):
            rows += s.run([t], output_names)
    assert together == alone
    assert alone[0] != alone[1]


@pytest.mark.parametrize("version", VERSIONS)
@pytest.mark.parametrize("integrator", INTEGRATORS, ids=integrator_id)
def test_reset_and_rerun_gives_identical_results(fmu_dir, output_names, version, integrator):
    s = Slave(fmu_dir(version), version)
    runs = []
    for cycle in range(5):
        s.init(**dict(SMALL, integrator=integrator))
        assert s.get("time") == 0.0
        runs.append(s.run(TIMES, output_names))
        # change what a reset must undo: a tunable, an input, and a fixed parameter next time
        s.set(mu=0.7, F_T_ext=0.001)
        s.run([1.5], output_names)
        s.fmu.terminate()
        s.reset()
        assert s.get("mu") == 0.1 and s.get("F_T_ext") == 0.0 and s.get("n_segments") == 2000
    assert all(run == runs[0] for run in runs)


def test_fmi2_instance_name_is_copied(fmu_dir):
    s = Slave(fmu_dir(2), 2)
    name = create_string_buffer(b"the_caller_s_name")
    component = s.fmu.fmi2Instantiate(ctypes.cast(name, c_char_p), 1, s.md.guid.encode(), b"",
                                      byref(s._callbacks), 0, 0)
    assert component
    name.value = b"overwritten_later"  # the caller may reuse or free its string
    vr = (ctypes.c_uint * 1)(999)
    value = (ctypes.c_double * 1)()
    assert s.fmu._functions["fmi2GetReal"](component, vr, 1, value) != 0
    assert s.logged_instance_names[-1] == "the_caller_s_name"
    s.fmu.fmi2FreeInstance(component)


def test_fmi3_instance_name_may_be_freed_by_the_caller(fmu_dir):
    """FMI 3.0's logger does not receive the name: check the instance outlives the
    caller's string (the copy is the FMI 2.0 test's)."""
    s = Slave(fmu_dir(3), 3)
    name = create_string_buffer(b"the_caller_s_name")
    component = s.fmu._functions["fmi3InstantiateCoSimulation"](
        ctypes.cast(name, c_char_p), s.md.guid.encode(), b"", False, True, False, False, None, 0,
        None, s.fmu.logMessage, s.fmu.intermediateUpdate)
    assert component
    ctypes.memset(name, ord("x"), len(name) - 1)
    # the trace of the calls, which loggingOn alone does not turn on
    assert s.fmu._functions["fmi3SetDebugLogging"](component, True, 0, None) == 0
    assert s.fmu._functions["fmi3Reset"](component) == 0
    assert any(m.startswith("fmi3Reset") for _, _, m in s.messages)
    s.fmu.fmi3FreeInstance(component)


def heap_in_use():
    """Bytes the C heap has handed out (glibc's mallinfo2: small and mmapped blocks)."""
    class MallInfo2(ctypes.Structure):
        _fields_ = [(f, ctypes.c_size_t) for f in ("arena", "ordblks", "smblks", "hblks", "hblkhd",
                                                   "usmblks", "fsmblks", "uordblks", "fordblks",
                                                   "keepcost")]
    libc = ctypes.CDLL(None)
    libc.mallinfo2.restype = MallInfo2
    info = libc.mallinfo2()
    return info.uordblks + info.hblkhd


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


# 1000 cycles of a leak as small as one instance name (a 32-byte heap block) would
# exceed the heap bound; the resident-set bound (1 MiB) is a coarse second check, which a
# leak the heap count does not see (e.g. mapped memory) would still cross.
CYCLES = 1000
HEAP_GROWTH_BOUND = 16 * 1024
RSS_GROWTH_BOUND = 1024 * 1024


@pytest.mark.parametrize("version", VERSIONS)
def test_instantiate_free_cycles_leak_nothing(fmu_dir, version):
    s = Slave(fmu_dir(version), version)

    def cycle():
        s.instantiate()
        s.set(n_segments=16)
        s.init()
        s.step_to(0.01)
        state = s.get_state()
        restored = s.deserialize(s.serialize(state))
        s.set_state(restored)
        s.free_state(state)
        s.free_state(restored)
        s.fmu.terminate()
        getattr(s.fmu, f"fmi{version}FreeInstance")(s.fmu.component)

    getattr(s.fmu, f"fmi{version}FreeInstance")(s.fmu.component)
    for _ in range(100):  # warm up: first-use allocations of Python, fmpy and libc
        cycle()
    gc.collect()
    heap, rss = heap_in_use(), resident_bytes()
    for _ in range(CYCLES):
        cycle()
    gc.collect()
    heap_growth, rss_growth = heap_in_use() - heap, resident_bytes() - rss
    print(f"FMI {version}: {CYCLES} cycles: heap {heap_growth:+d} B, RSS {rss_growth:+d} B")
    assert heap_growth < HEAP_GROWTH_BOUND
    assert rss_growth < RSS_GROWTH_BOUND
