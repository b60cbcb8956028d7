"""The package's runs in one process (tribo.fmu.library, tribo.batch.particle): an FMU is
unpacked and loaded once per process and removed when the process ends, its instances
stay independent (threads of one Dask worker included), and a run that reads only its end
gives the last row of the same run recorded at any interval, bit for bit."""

import concurrent.futures
import os
import subprocess
import sys
import textwrap

import pytest

import tribo
from tribo.batch.particle import run_to_end, simulate
from tribo.fmu import FmuImage, Instance, Rows, record
from tribo.fmu.charge_models import charge_models
from tribo.fmu.names import start_value
from tribo.populations.feed import Feed, outputs, run_particle, specs_of

# a short chute: each particle a few impacts
SHORT = {"chute_length": 0.02}
TIMING = ("cpu_s", "wall_s")


@pytest.fixture(scope="module")
def si_image():
    return FmuImage.load(tribo.find_fmu(variant="si"))


def particle_specs(image, n, seed=3, t_end=1.0):
    depth = start_value(image.model_description(), "cylinder_length")
    return specs_of(Feed(chute=SHORT), n, seed, t_end, {"cylinder_length": depth})


def without_timing(row):
    return {k: v for k, v in row.items() if k not in TIMING}


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


def test_runs_in_threads_of_one_process_give_the_serial_numbers(si_image):
    """As on the local Dask cluster: several threads run particles of one FMU at once."""
    specs = particle_specs(si_image, 8)
    serial = [without_timing(run_particle(si_image, s).row) for s in specs]
    with concurrent.futures.ThreadPoolExecutor(4) as pool:
        threaded = [without_timing(r.row) for r in pool.map(lambda s: run_particle(si_image, s),
                                                            specs)]
    assert threaded == serial
    assert len({r["time_end"] for r in serial}) > 1  # different particles


def test_a_run_that_fails_quotes_its_own_fmus_message_beside_running_ones(si_image):
    spec = particle_specs(si_image, 1)[0]
    bad = dict(spec.params, density=-1.0)
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        good = pool.submit(run_to_end, si_image, spec.params, spec.t_end, ["exited"])
        failed = pool.submit(run_to_end, si_image, bad, spec.t_end, ["exited"])
        with pytest.raises(RuntimeError, match=r"the FMU failed in setting the parameters: "
                                               r"density = -1"):
            failed.result()
        assert all("density" not in m for _, _, m in good.result().messages)


def test_a_particles_row_is_the_last_row_of_its_recorded_run(si_image):
    """A population's row comes from one step to the horizon; recorded at the population's
    old grid (t_end / 100) the run ends with the same numbers, bit for bit."""
    models = charge_models(si_image.model_description())
    for spec in particle_specs(si_image, 4, seed=5):
        row = run_particle(si_image, spec).row
        series = simulate(si_image, spec.params, spec.t_end, spec.t_end / 100,
                          outputs(models)).series
        last = series.iloc[-1]
        assert row["time_end"] == last["time"]
        for name in outputs(models):
            assert row[name] == last[name], name


@pytest.mark.parametrize("version", [2, 3])
@pytest.mark.parametrize("chute_length, t_end", [(0.02, 1.0), (0.3, 0.05)],
                         ids=["to the exit", "to the horizon"])
def test_the_end_alone_is_the_last_row_of_any_record_interval(version, chute_length, t_end):
    kw = dict(size=1e-3, epsilon=0.6, drop_height=1e-3, chute_length=chute_length, t_end=t_end,
              fmu=version)
    end = tribo.run_si("PE", "steel", record_interval=None, **kw)
    assert len(end) == 1
    for interval in (1e-3, t_end / 7):
        recorded = tribo.run_si("PE", "steel", record_interval=interval, **kw)
        assert end.iloc[0].equals(recorded.iloc[-1])
        assert list(end.columns) == list(recorded.columns)
        assert (end.dtypes == recorded.dtypes).all()


def test_fmi2s_one_step_to_the_end_is_not_cut_by_the_work_limit():
    """The paper's fixed step to 150: over the default work limit in one step, which FMI
    2.0 cannot go on from; the end-only run takes the limit off, with the same numbers."""
    kw = dict(t_end=150.0, fmu=2, integrator=0, outputs=["X", "Q_static"])
    end = tribo.run(record_interval=None, **kw)
    recorded = tribo.run(record_interval=50.0, **kw)
    assert end.iloc[0].equals(recorded.iloc[-1])


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


def bits(value):
    """A value's type and bits (-0.0 is not 0.0, NaN is NaN)."""
    import struct
    return (type(value), struct.pack("<d", value) if isinstance(value, float) else value)


@pytest.mark.parametrize("version", [2, 3])
def test_values_set_and_read_at_once_are_those_set_and_read_by_name(version):
    """set_parameters (one FMI call per run of one type) and get_many (one per type) against
    Instance.set and Instance.get, name by name: the same run, every scalar variable read
    back the same to the bit and of the same Python type; a layout made once per loaded FMU
    serves a second instance."""
    image = FmuImage.load(tribo.find_fmu(version, variant="si"))
    md = image.model_description()
    spec = particle_specs(image, 2)[1]
    from tribo.fmu.names import to_fmu
    params = to_fmu(md, spec.params)
    params["charge_model_static"] = 1  # a Boolean amid the floats, an enumeration and an integer
    names = [v.name for v in md.modelVariables if not v.dimensions
             and v.type in ("Real", "Float64", "Integer", "Int32", "Int64", "UInt64",
                            "Boolean", "Enumeration")]
    read = []
    for at_once in (False, True, True):
        with Instance(image) as s:
            if at_once:
                s.set_parameters(params)
            else:
                for name, value in params.items():
                    v = s.variables[name]
                    s.set(**{name: float(value) if v.type in ("Real", "Float64") else int(value)})
            s.init(0.0, spec.t_end)
            s.step_to(spec.t_end)
            read.append({n: bits(x) for n, x in
                         (s.get_many(names) if at_once else {n: s.get(n) for n in names}).items()})
    assert len(names) > 50 and read[0] == read[1] == read[2]
