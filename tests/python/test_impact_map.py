"""Charge-per-impact maps (tribo.impact.episode, tribo.impact.map, tribo impact-map): one episode
ends at its lift-off or its time limit, the lookup against direct episodes at grid points and
between them, resuming, bad input in one line, the figure's legends."""

import numpy as np
import pytest

import tribo
from tribo.batch.executors import SerialExecutor
from tribo.cli.main import main as tribo_command
from tribo.fmu import FmuImage
from tribo.impact import plot as impact_plot
from tribo.impact.episode import Grid, ImpactError, episode_specs, run_episode
from tribo.impact.map import ImpactMap, run_impact_map
from figure_checks import assert_legends_cover_no_data

SETTINGS = {"size": 1e-3, "n_segments": 400}


@pytest.fixture(scope="module")
def si_image():
    return FmuImage.load(tribo.find_fmu(variant="si"))


def episode(image, speed, angle_deg, phi0_deg, epsilon, limit=200.0):
    grid = Grid.of(speed=[speed], angle_deg=[angle_deg], phi0_deg=[phi0_deg], epsilon=[epsilon])
    return run_episode(image, episode_specs(grid, "PE", "steel", SETTINGS, limit)[0]).row


def test_a_head_on_impact_of_a_disc_rebounds_straight_up_once(si_image):
    row = episode(si_image, 2.0, 90.0, 0.0, 1.0)
    assert row["lifted_off"] == 1
    # straight back up, slower (the dashpot, nu = 0.3), no spin, one contact of ~pi t*: a
    # head-on disc meets no tangential force, so the angle and the spin were measured exact
    # (90 and 0), and the run ends at the end of its one contact, also to the bit; the
    # speed's and the contact's ranges are what the physics allows (measured 0.73 of the
    # speed in, and 3.26 t*)
    assert row["rebound_angle_deg"] == 90.0
    assert 0.2 * 2.0 < row["rebound_speed"] < 2.0
    assert row["rebound_omega"] == 0.0
    assert 2.0 * row["t_star"] < row["contact_time"] < 5.0 * row["t_star"]
    assert row["time_end"] == row["contact_time"]
    assert row["charge_static"] < 0.0  # PE on steel charges negatively


def test_an_episode_that_outlasts_its_limit_counts_as_sustained_contact(si_image):
    row = episode(si_image, 2.0, 90.0, 0.0, 1.0, limit=0.5)  # half a t*: still pressing in
    assert row["lifted_off"] == 0
    assert row["time_end"] == 0.5 * row["t_star"]  # the limit, measured to the bit


@pytest.fixture(scope="module")
def small_map(si_image, tmp_path_factory):
    out = tmp_path_factory.mktemp("map")
    grid = Grid.of(speed=[1.0, 3.0], angle_deg=[30.0, 60.0, 90.0], phi0_deg=[0.0, 30.0], epsilon=[0.5, 1.0])
    titles = []
    original = impact_plot.save
    with pytest.MonkeyPatch.context() as mp:  # the figure as written, its title kept
        mp.setattr(impact_plot, "save", lambda fig, path: titles.append(fig._suptitle.get_text())
                   or original(fig, path))
        report = run_impact_map(grid, "PE", "steel", SETTINGS, 200.0, si_image, str(out),
                                SerialExecutor(), progress=False)
    assert report.table is not None and not report.failed
    report.titles = titles
    return str(out), report


def test_the_map_is_written_with_its_metadata(small_map):
    out, report = small_map
    m = ImpactMap.load(out)
    assert len(m.table) == 24 and list(m.table.columns[:4]) == ["speed", "angle_deg", "phi0_deg", "epsilon"]
    meta = m.metadata
    assert meta["particle"] == "PE" and meta["wall"] == "steel"
    assert meta["grid"]["angle_deg"]["values"] == [30.0, 60.0, 90.0]
    assert len(meta["model"]["fmu_sha256"]) == 64 and meta["model"]["instantiation_token"]
    # the grain's charge, the spheroid's by default (docs/model.md section 8c)
    assert meta["columns"]["charge_static"].startswith("C per impact, the grain's: the spheroid's")
    assert meta["columns"]["charge_to_mass_sliding"] == "C/kg"
    # what the charges in C depend on beyond the grid, in the table and the metadata: the
    # size as set, the cylinder depth and the grain's geometry (1: the spheroid) as the
    # FMU's defaults
    assert m.set_up == {"particle": "PE", "wall": "steel", "size": 1e-3, "cylinder_length": 1e-3,
                        "grain_geometry": 1, "n_segments": 400}
    for column, value in (("particle", "PE"), ("wall", "steel"), ("size", 1e-3), ("cylinder_length", 1e-3)):
        assert (m.table[column] == value).all(), column
    assert report.titles == ["charge per impact: PE on steel, size 2a = 0.001 m, the spheroid's "
                             "charge"]


def test_the_lookup_is_the_episode_at_grid_points(small_map, si_image):
    out, _ = small_map
    m = ImpactMap.load(out)
    for speed, angle, phi0, eps in [(1.0, 30.0, 0.0, 0.5), (3.0, 60.0, 30.0, 1.0)]:
        direct = episode(si_image, speed, angle, phi0, eps)
        for q in ("charge_static", "charge_sliding", "rebound_speed", "contact_time"):
            assert m(q, speed, angle, phi0, eps) == direct[q], q


def test_the_lookup_between_grid_points(small_map, si_image):
    out, _ = small_map
    m = ImpactMap.load(out)
    # linear between the neighbours: midway, their mean (measured to the bit)
    a = m("charge_static", 1.0, 60.0, 0.0, 0.5)
    b = m("charge_static", 3.0, 60.0, 0.0, 0.5)
    assert m("charge_static", 2.0, 60.0, 0.0, 0.5) == 0.5 * (a + b)
    # and close to the episode run there: the static charge per impact of a disc grows
    # smoothly with the speed (measured: the linear lookup is 2.32% below the episode at
    # 2 m/s, head-on; bound: that error with a margin of 1.5)
    direct = episode(si_image, 2.0, 90.0, 0.0, 1.0)
    looked_up = m("charge_static", 2.0, 90.0, 0.0, 1.0)
    assert looked_up == pytest.approx(direct["charge_static"], rel=1.5 * 0.0232, abs=0)
    # arrays broadcast
    values = m("rebound_speed", np.array([1.0, 2.0, 3.0]), 90.0, 0.0, 1.0)
    assert values.shape == (3,) and values[0] < values[1] < values[2]


def test_a_point_outside_the_grid_is_refused_naming_the_axis(small_map):
    m = ImpactMap.load(small_map[0])
    with pytest.raises(ValueError, match=r"angle_deg = 20 is outside the map's grid \[30, 90\]"):
        m("charge_static", 2.0, 20.0, 0.0, 0.5)
    with pytest.raises(KeyError, match="not a column"):
        m("charge", 2.0, 60.0, 0.0, 0.5)


def test_a_map_resumes_after_an_interruption(tmp_path, si_image, small_map):
    grid = Grid.of(speed=[1.0, 3.0], angle_deg=[30.0, 60.0, 90.0], phi0_deg=[0.0, 30.0], epsilon=[0.5, 1.0])
    part = run_impact_map(grid, "PE", "steel", SETTINGS, 200.0, si_image, str(tmp_path), SerialExecutor(),
                          progress=False, max_runs=5, figure=False)
    assert part.table is None and part.executed == 5
    rest = run_impact_map(grid, "PE", "steel", SETTINGS, 200.0, si_image, str(tmp_path), SerialExecutor(),
                          progress=False, figure=False)
    assert (rest.executed, rest.skipped) == (19, 5)
    whole = small_map[1].table
    assert rest.table[["charge_static", "charge_sliding", "rebound_v"]].equals(
        whole[["charge_static", "charge_sliding", "rebound_v"]])


@pytest.mark.parametrize("axes, says", [
    (dict(speed=[0.0], angle_deg=[90.0], phi0_deg=[0.0], epsilon=[1.0]), "speed = 0"),
    (dict(speed=[1.0], angle_deg=[95.0], phi0_deg=[0.0], epsilon=[1.0]), "angle_deg = 95"),
    (dict(speed=[1.0], angle_deg=[0.0], phi0_deg=[0.0], epsilon=[1.0]), "angle_deg = 0"),
    (dict(speed=[3.0, 1.0], angle_deg=[90.0], phi0_deg=[0.0], epsilon=[1.0]), "must increase"),
    (dict(speed=[1.0], angle_deg=[90.0], phi0_deg=[0.0], epsilon=[1.5]), "epsilon = 1.5"),
    (dict(speed=[1.0], angle_deg=[90.0], phi0_deg=[0.0]), "missing epsilon"),
    (dict(speed=[1.0], angle=[90.0], phi0_deg=[0.0], epsilon=[1.0]), "unknown angle"),
])
def test_a_bad_grid_is_one_line(axes, says):
    with pytest.raises(ImpactError, match=says) as e:
        Grid.of(**axes)
    assert "\n" not in str(e.value)


@pytest.mark.parametrize("argv, says", [
    (["--speed", "1", "--angle-deg", "90", "--limit", "0"], "time limit"),
    (["--speed", "1", "--angle-deg", "90", "--limit", "1e308"], "at most 1e+12"),
    (["--speed", "1:5", "--angle-deg", "90"], "expected a:b:n"),
    (["--speed", "1", "--angle-deg", "90", "--wall", "wood"], "unknown wall material 'wood'"),
    (["--speed", "1", "--angle-deg", "90", "--set", "size=-1"], "size = -1 is invalid: the valid range is 2e-07 <= size <= 2"),
    (["--speed", "1", "--angle-deg", "90", "--set", "semi_major_axis=1e-3"], "the package takes this parameter as size"),
    (["--speed", "2000", "--angle-deg", "90"], "speed = 2000"),
])
def test_bad_input_to_the_command_is_one_line(tmp_path, capsys, argv, says):
    try:
        status = tribo_command(["impact-map", *argv, "--out", str(tmp_path / "m"), "--serial"])
    except SystemExit as e:  # argparse's own errors
        status = e.code
    assert status == 2
    err = capsys.readouterr().err
    assert says in err and len(err.strip().splitlines()) == 1, err
    assert not (tmp_path / "m" / "episodes.csv").exists()


def test_the_figure_has_a_legend_on_every_panel(small_map, monkeypatch, tmp_path):
    figures = []
    monkeypatch.setattr(impact_plot, "save", lambda fig, path: figures.append(fig) or path)
    impact_plot.write_impact_figure(small_map[1].table, ("static", "sliding"),
                                    str(tmp_path / "f.png"), "t")
    assert_legends_cover_no_data(figures[0])
    assert len(figures[0].axes) == 4
    for ax in figures[0].axes:
        assert ax.get_legend() is not None and len(ax.get_legend().get_texts()) == 2
        assert ax.get_xlabel() and ax.get_ylabel()


@pytest.mark.parametrize("speed, angle_deg, epsilon", [(1.0, 90.0, 1.0), (4.0, 30.0, 0.6)])
def test_the_charge_of_a_first_impact_is_sigma0_over_the_charged_area(si_image, speed, angle_deg,
                                                                      epsilon):
    """A first impact on an uncharged grain with instantaneous transfer (the SI default
    charging time 0, docs/model.md section 5c), |sigma0| below the gas's limit of the patch
    (section 8e): the static model's charge is sigma0 times the area the patch touched
    (measured equal to 4e-16 relative, for the head-on 2 mm PE sphere and an oblique spheroid
    alike)."""
    grid = Grid.of(speed=[speed], angle_deg=[angle_deg], phi0_deg=[0.0], epsilon=[epsilon])
    sigma0 = -1e-5
    spec = episode_specs(grid, "PE", "steel", {"size": 2e-3, "sigma0": sigma0}, 200.0)[0]
    row = run_episode(si_image, spec).row
    assert row["lifted_off"] == 1 and row["end_reason"] == 2
    assert row["charged_area"] > 0.0
    assert row["charge_static"] / row["charged_area"] == pytest.approx(sigma0, rel=1e-12, abs=0)


def test_an_episode_that_settles_on_the_plate_ends_at_rest_and_is_said_apart(tmp_path, capsys):
    """Arriving at 1e-6 m/s the grain does not lift off: it settles and the run ends at
    rest within microseconds, its "rebound" the state it rests in; a grazing 0.01 m/s
    arrival at 0.01 degrees slides on past the 200 t* limit, still in contact (both seen in
    the runs). The map's rows say which and the closing line counts each."""
    out = tmp_path / "slow"
    assert tribo_command(["impact-map", "--speed", "1e-6,0.01", "--angle-deg", "0.01,90",
                          "--epsilon", "0.5", "--out", str(out), "--serial", "--no-progress"]) == 0
    said = capsys.readouterr().out
    m = ImpactMap.load(str(out))
    rows = m.table.set_index(["speed", "angle_deg"])
    assert list(rows.loc[(1e-6, 90.0), ["lifted_off", "end_reason"]]) == [0, 3]
    assert rows.loc[(1e-6, 90.0), "rebound_speed"] == 0.0
    assert list(rows.loc[(0.01, 0.01), ["lifted_off", "end_reason"]]) == [0, 0]
    assert list(rows.loc[(0.01, 90.0), ["lifted_off", "end_reason"]]) == [1, 2]
    reasons = m.table["end_reason"]
    assert (f"impact map: {(reasons == 2).sum()} of 4 episodes lifted off, "
            f"{(reasons == 3).sum()} came to rest on the plate (no rebound), "
            f"{(reasons == 0).sum()} still in contact at the time limit of 200 t*") in said
    assert m.metadata["columns"]["charged_area"].startswith("m2")
    assert (m.table["charged_area"] > 0).all()
    assert m("charged_area", 0.01, 90.0, 0.0, 0.5) == m.table["charged_area"].iloc[-1]


def test_the_figure_rings_the_points_that_did_not_lift_off(small_map, monkeypatch, tmp_path):
    table = small_map[1].table.copy()
    held = (table["speed"] == 3.0) & (table["angle_deg"] == 30.0)
    table.loc[held, "lifted_off"] = 0
    figures = []
    monkeypatch.setattr(impact_plot, "save", lambda fig, path: figures.append(fig) or path)
    impact_plot.write_impact_figure(table, ("static",), str(tmp_path / "f.png"), "t")
    angle_panel, speed_panel = figures[0].axes
    texts = [t.get_text() for t in angle_panel.get_legend().get_texts()]
    assert texts == ["ε = 0.5", "ε = 1", impact_plot.SUSTAINED]
    rings = [line for line in angle_panel.get_lines() if line.get_label() == impact_plot.SUSTAINED]
    assert len(rings) == 2 and all(list(r.get_xdata()) == [30.0] for r in rings)
    assert len(speed_panel.get_legend().get_texts()) == 2  # the head-on slice lifted off
    assert_legends_cover_no_data(figures[0])


def test_the_title_names_the_cylinders_depth_only_where_the_grain_is_the_cylinder():
    from tribo.impact.map import set_up_title
    base = {"particle": "PE", "wall": "steel", "size": 1e-3, "cylinder_length": 2e-3}
    assert set_up_title(dict(base, grain_geometry=0)).endswith("cylinder depth ℓ = 0.002 m")
    assert set_up_title(dict(base, grain_geometry=1)).endswith("the spheroid's charge")
