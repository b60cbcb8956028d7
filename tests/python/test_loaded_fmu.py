"""The package's runs in one process (tribo.fmu.library): an FMU is unpacked and loaded
once per process and removed when the process ends, and its instances stay independent;
outputs read in rows are the single getters' values."""

import os
import subprocess
import sys
import textwrap

import pytest

import tribo
from tribo.fmu import FmuImage, Instance, Rows, record


@pytest.fixture(scope="module")
def si_image():
    return FmuImage.load(tribo.find_fmu(variant="si"))


def test_instances_of_one_image_share_the_unpacked_fmu_but_nothing_they_change(si_image):
    a = Instance(si_image, name="a")
    b = Instance(si_image, name="b")
    try:
        assert a.fmu is not b.fmu and a.fmu.component != b.fmu.component
        assert a.fmu.unzipDirectory == b.fmu.unzipDirectory  # unpacked once
        assert os.path.isdir(a.fmu.unzipDirectory)
        # one refuses a value: its log holds the refusal, the other's nothing
        with pytest.raises(Exception):
            a.set_parameters({"epsilon": 2.0})
        assert a.errors() and "epsilon" in a.errors()[-1]
        assert b.messages == []
        b.set_parameters({"epsilon": 0.5})
        assert b.get("epsilon") == 0.5 and a.get("epsilon") != 0.5
    finally:
        a.free()
        b.free()
    # freeing instances leaves the process's library loaded: a new one runs
    with Instance(si_image) as c:
        c.init(0.0, 1e-3)
        assert c.step_to(1e-3)


def test_rows_read_every_type_as_the_single_getters_do(si_image):
    names = ["x", "in_contact", "impacts", "motion_class", "assumption_warnings", "exited"]
    with Instance(si_image) as s:
        s.init(0.0, 0.05)
        reached, table = record(s, [0.0, 0.01, 0.05], names)
        singles = [s.get(n) for n in names]
        rows = Rows(s, names, capacity=1)
        for _ in range(3):  # grows past its capacity
            rows.read()
    assert table.shape == (3, len(names)) and list(reached) == [0.0, 0.01, 0.05]
    assert list(table[-1]) == [float(v) for v in singles]
    assert (rows.table() == table[-1]).all()


def test_the_unpacked_fmu_is_removed_when_the_process_ends(tmp_path):
    """In the main process (atexit) and in a spawned child (as Dask's worker processes
    are), which leaves without atexit."""
    script = textwrap.dedent(f"""
        import multiprocessing, sys
        import tribo
        from tribo.fmu import FmuImage, Instance

        def directory(queue):
            with Instance(FmuImage.load(tribo.find_fmu(variant="si"))) as s:
                queue.put(s.fmu.unzipDirectory)

        if __name__ == "__main__":
            context = multiprocessing.get_context("spawn")
            queue = context.Queue()
            child = context.Process(target=directory, args=(queue,))
            child.start()
            print(queue.get())
            child.join()
            assert child.exitcode == 0
            directory(queue)
            print(queue.get())
    """)
    path = tmp_path / "run.py"
    path.write_text(script)
    out = subprocess.run([sys.executable, str(path)], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    child_dir, own_dir = out.stdout.split()
    assert child_dir != own_dir
    assert not os.path.exists(child_dir) and not os.path.exists(own_dir)
    assert all(os.path.basename(d).startswith("tribo_fmu_") for d in (child_dir, own_dir))
