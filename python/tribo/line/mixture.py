"""Grains through the line: a population of one particle material, or a binary mixture of
two on one chute wall, at one voltage or a sweep of voltages, into an output folder.

The feed (populations.feed.Feed: distributions of shape, size, orientation, drop) is drawn
once with the seed; a mixture's grains are the first n_a of the draw made of material A, the
rest of B, n_a from the mass fraction of A (`fraction`) and the densities (the draw's
grains are alike but for the material, so a grain's mean mass is in proportion to its
density): n_a = round(n f/rho_a / (f/rho_a + (1 - f)/rho_b)). The fed masses actually
drawn are reported (a draw of n grains has the fraction f up to its sampling spread). Each
grain also draws its entry point across the gap, x_entry uniform over the feed's width
`feed_width` centred on the gap's centre (a feed slot; 0 puts every grain on the centre
line, where any charge, however small, carries it to its side).

Each grain is one task (grain.run_line_grain): the chute once, the separator at every
voltage. Rows go into particles.csv as they finish (batch.sweep.run_sweep: resumable, a
progress bar), each grain's landings at every voltage into landings/<key>.csv first; when
all have run, the folder gets

    particles.csv  a row per grain: its material, wall, seed, every parameter of its chute
                   run, the chute's results (populations.feed), charge_to_mass (the ratio
                   the separator got), mass (the separator's 3D equivalent, kg), the landing
                   at the first voltage (grain.LANDING_COLUMNS)
    landings.csv   a row per grain and voltage: key, particle, mass, voltage, the landing
    line.csv       a row per voltage: the mass fed, in each product, on each plate, airborne,
                   not out of the chute (at rest on it, or still on it at the horizon), per
                   material, and the number of grains fed, at rest and at the horizon; a
                   mixture's grade and recovery of each product and its separation
    bins.csv       the mass per voltage, bin and material
    line.png       a sweep's figure (grade and recovery against the voltage)
    line.json      the set-up

The products: a splitter at x = `splitter` (default 0, the centre line between the bins of
the negative and the positive plate's side) divides the bins; a grain landed at x_end <
splitter, or caught on the plate at -gap/2, is collected on the negative-x side, the rest on
the positive-x side (a plate's grains are scraped into the product below it). For U > 0 a
positive grain drifts to -x (docs/separator.md): the material whose sigma0 against the wall
is positive is the target of the -x product, the other of the +x one (mirrored for U < 0).
grade = target's mass in its product / the product's mass; recovery = target's mass in its
product / the target's fed mass (grains that do not leave the chute, or are still falling
at the separator's horizon, count as fed and not collected). separation = the two
recoveries' sum less 1: 0 for a random split of the feed (whose grades are the feed's mass
shares, near 0.5 for an even mixture), 1 for a complete one.

A grain that does not leave the chute never enters the separator: it came to rest on the
chute (its run ended there, docs/model.md section 3c) or was still on it at the chute's
horizon `t_end`. Each is counted apart (line.csv's at_rest_<m> and at_horizon_<m> masses,
n_at_rest_<m> and n_at_horizon_<m> grains; not_exited_<m> is their sum), in the figure's
title and in the command's closing line.
"""

import json
import math
import os
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from ..batch.job import Job, Report
from ..batch.results import KEY
from ..batch.specs import RunSpec, check_count
from ..batch.sweep import keys_of, read_many_series, run_sweep
from ..fmu.names import start_value
from ..fmu.parameters import check_values
from ..materials import Materials, material, pair_sigma0, table_of, with_pair
from ..populations.feed import (END_AT_REST, Feed, FeedError, check_horizon, draw,
                                particle_parameters)
from ..populations.feed_variables import DEFAULT_CHUTE
from .defaults import DEFAULT_FEED_WIDTH, DEFAULT_PAIR, DEFAULT_WALL
from .grain import (LineError, LineImages, charge_model_settings, check_separator,
                    chute_params_of, load_images, result_columns, run_line_grain)

PARTICLES, LANDINGS, TABLE, BINS, FIGURE, METADATA = ("particles.csv", "landings.csv", "line.csv",
                                                      "bins.csv", "line.png", "line.json")
LANDINGS_DIR = "landings"
STEPS_PER_RUN = 100  # the chute's record_interval is t_end / 100 in its key (as a population's)
WORK_LIMIT = 2**31 - 1


@dataclass
class Line:
    """What grains are fed and how the line is set up (see the module's text)."""

    particles: tuple = DEFAULT_PAIR  # one material (a population) or two (a mixture)
    wall: str = DEFAULT_WALL
    fraction: float = 0.5  # mass fraction of the first material in a mixture
    distributions: dict = field(default_factory=dict)
    chute: dict = field(default_factory=lambda: dict(DEFAULT_CHUTE))
    settings: dict = field(default_factory=dict)  # any other SI chute parameter
    separator: dict = field(default_factory=dict)  # the separator's settings (grain.SEPARATOR_SETTINGS)
    feed_width: float = DEFAULT_FEED_WIDTH
    charge_model: str = "static"
    splitter: float = 0.0
    # a materials file (tribo.materials) the particles' values come from; None: the package's
    materials: Materials | str | None = None

    def check(self, models=None) -> None:
        """LineError, one line, for a value the line cannot run with; the charge model too
        where the chute's `models` are given."""
        if isinstance(self.particles, str):
            self.particles = (self.particles,)
        self.particles = tuple(self.particles)
        if self.materials is not None:
            self.materials = table_of(self.materials)
        if len(self.particles) not in (1, 2):
            raise LineError(f"particles = {self.particles!r}: one material or two")
        keys = [material(p, "particle").key for p in self.particles]
        material(self.wall, "wall")
        if len(keys) == 2 and keys[0] == keys[1]:
            raise LineError(f"particles = {self.particles!r}: a mixture of two different materials")
        if not (0 < self.fraction < 1):
            raise LineError(f"fraction = {self.fraction!r}: the mass fraction of "
                            f"{self.particles[0]}, between 0 and 1 (exclusive)")
        if not (math.isfinite(self.feed_width) and self.feed_width >= 0):
            raise LineError(f"feed_width = {self.feed_width!r}: a width in m, at least 0")
        if not math.isfinite(self.splitter):
            raise LineError(f"splitter = {self.splitter!r}: a position across the gap, m")
        if "x_entry" in self.separator:
            raise LineError("x_entry is drawn for each grain across feed_width: give feed_width")
        if models is not None:
            charge_model_settings(self.charge_model, models)
        if len(keys) == 2:
            sigma0 = [self.sigma0(k) for k in keys]
            if math.copysign(1, sigma0[0]) == math.copysign(1, sigma0[1]):
                raise LineError(f"{keys[0]} and {keys[1]} charge with the same sign on "
                                f"{self.wall} (sigma0 {sigma0[0]:g} and {sigma0[1]:g} C/m2): a "
                                f"mixture needs opposite polarities")

    def sigma0(self, particle: str) -> float:
        """The particle's sigma0 on the wall: the settings', else the materials'."""
        if "sigma0" in self.settings:
            return float(self.settings["sigma0"])
        return pair_sigma0(particle, self.wall, materials=self.materials)

    def settings_of(self, particle: str) -> dict:
        """The chute's settings of a grain of `particle`: the line's, over the materials
        file's values of the pair where one is given."""
        return with_pair(particle, self.wall, self.settings, self.materials)

    def describe(self) -> dict:
        self.check()
        # a materials file by its digest (its values are in the particles' rows); no key
        # without one, so that a folder of the package's table keeps its record
        given = {} if self.materials is None else {
            "materials": {"file": self.materials.source, "sha256": self.materials.sha256}}
        return {**given, "particles": [material(p, "particle").key for p in self.particles],
                "wall": material(self.wall, "wall").key, "fraction": self.fraction,
                "distributions": dict(Feed(self.particles[0], self.wall, self.distributions)
                                      .describe()["distributions"]),
                "chute": dict(DEFAULT_CHUTE, **self.chute), "settings": dict(self.settings),
                "separator": dict(self.separator), "feed_width": self.feed_width,
                "charge_model": self.charge_model, "splitter": self.splitter}


def counts(line: Line, n: int) -> list[int]:
    """How many of the n grains are of each material."""
    if len(line.particles) == 1:
        return [n]
    rho = [material(p, "particle", materials=line.materials).density for p in line.particles]
    f = line.fraction
    n_a = int(round(n * (f / rho[0]) / (f / rho[0] + (1 - f) / rho[1])))
    return [n_a, n - n_a]


def line_specs(line: Line, n: int, seed: int, t_end: float, models, md=None) -> list[RunSpec]:
    """Each grain's run: its material, entry point and chute parameters (one of the chute's
    charge models `models` on: the line's). Where a materials file gives one material a
    charging parameter it does not give the other, the other's is the chute FMU's start
    value (its description `md`)."""
    line.check(models)
    if not (isinstance(t_end, (int, float)) and math.isfinite(t_end) and t_end > 0):
        raise FeedError(f"the horizon t_end must be a positive number of seconds, got {t_end!r}")
    settings = dict(line.settings, **charge_model_settings(line.charge_model, models))
    base = Feed(line.particles[0], line.wall, dict(line.distributions), dict(line.chute), settings)
    drawn = draw(base, n, seed)
    rng = np.random.default_rng([seed, 1])  # the entry points: a stream of their own
    x_entry = (rng.random(n) - 0.5) * line.feed_width
    specs, start = [], 0
    own = {name: line.settings_of(name) for name in line.particles}
    for name, settings in own.items():  # the runs of one line set the same parameters
        for key in set().union(*own.values()) - set(settings):
            value = None if md is None else start_value(md, key)
            if value is None:
                raise LineError(f"{key} is set for {' and '.join(k for k in own if k != name)} "
                                f"but not for {name}: set it for both")
            settings[key] = value
    for name, count in zip(line.particles, counts(line, n)):
        feed = Feed(name, line.wall, dict(line.distributions), dict(line.chute),
                    dict(own[name], **charge_model_settings(line.charge_model, models)))
        rows = drawn.iloc[start:start + count].reset_index(drop=True)
        for i, params in enumerate(particle_parameters(feed, rows)):
            params["work_limit"] = WORK_LIMIT
            p = {"particle": material(name, "particle").key,
                 "x_entry": round(float(x_entry[start + i]), 12), **params}
            specs.append(RunSpec(p, float(t_end), float(t_end) / STEPS_PER_RUN))
        start += count
    return specs


def check_line(line: Line, specs: list[RunSpec], images: LineImages) -> None:
    """Every value checked by the FMUs before anything runs."""
    values = {}
    for s in specs:
        for name, value in chute_params_of(s.params).items():
            if name != "x_entry":
                values.setdefault(name, {})[value] = None
    check_values(images.chute, {k: list(v) for k, v in values.items()})
    # the chute's horizon the model resolves (every run failed at its first step beyond)
    check_horizon(images.chute, [RunSpec(chute_params_of(s.params), s.t_end) for s in specs])
    sizes = [s.params["size"] for s in specs]
    check_separator(images.separator, dict(images.settings, x_entry=line.feed_width / 2),
                    images.voltages, sizes)


def line_setup(line: Line, n: int, seed: int, t_end: float, voltages) -> dict:
    """What makes a line's folder this one (batch/folder.py's record)."""
    return {"n": n, "seed": seed, "t_end_s": t_end, "voltages": [float(v) for v in voltages],
            "line": line.describe()}


@dataclass(kw_only=True)
class LineReport(Report):
    """The grains' rows (`results`: particles.csv) and, once all have run, a row per grain
    and voltage (`landings`), per voltage (`table`: line.csv) and per bin (`bins`)."""

    landings: pd.DataFrame | None = None
    table: pd.DataFrame | None = None
    bins: pd.DataFrame | None = None


def run_line(line: Line, n: int, seed: int, t_end: float, images: LineImages, out: str, executor,
             *, specs=None, progress: bool = True, figure: bool = True,
             max_runs: int | None = None) -> LineReport:
    """The grains on the executor (entered by the caller, or a SerialExecutor), then, once
    all have run, the landings, the tally per voltage and bin, and the figure."""
    specs = specs if specs is not None else line_specs(line, n, seed, t_end, images.models)
    os.makedirs(out, exist_ok=True)
    described = line.describe()
    with open(os.path.join(out, METADATA), "w") as f:
        json.dump({**line_setup(line, n, seed, t_end, images.voltages), "chute_fmu": images.chute.name,
                   "separator_fmu": images.separator.name, "sha256": images.sha256}, f, indent=2)
    runs = run_sweep(specs, images, os.path.join(out, PARTICLES), executor,
                     series_dir=os.path.join(out, LANDINGS_DIR), max_runs=max_runs,
                     progress=progress, desc="grains", run=run_line_grain,
                     result_columns=result_columns(images.models),
                     constants={"wall": described["wall"], "seed": seed})
    report = LineReport(**vars(runs))
    report.files += [os.path.join(out, PARTICLES), os.path.join(out, METADATA)]
    if report.complete:
        report.landings = collect_landings(report.results, os.path.join(out, LANDINGS_DIR))
        report.landings.to_csv(os.path.join(out, LANDINGS), index=False, float_format="%.10g")
        report.table, report.bins = tally(report.landings, line,
                                          int(images.settings.get("n_bins", n_bins_of(images))))
        report.table.to_csv(os.path.join(out, TABLE), index=False, float_format="%.10g")
        report.bins.to_csv(os.path.join(out, BINS), index=False, float_format="%.10g")
        report.files += [os.path.join(out, f) for f in (LANDINGS, TABLE, BINS)]
        if figure and len(line.particles) == 2 and len(images.voltages) > 1:
            # matplotlib only when a figure is drawn: `import tribo` stays without it
            from .plot import write_line_figure
            first = report.table.iloc[0]
            keys = [material(p, "particle").key for p in line.particles]
            stayed = stayed_text(first, keys, t_end, sep="\n") \
                if sum(first[f"not_exited_{m}"] for m in keys) > 0 else ""
            report.files.append(write_line_figure(report.table, line, n, seed,
                                                  os.path.join(out, FIGURE), stayed))
    return report


class LineJob(Job):
    """Grains through the line into an output folder (batch/job.py's flow): n grains of
    `line` drawn with `seed`, the chute to `t_end` s, the separator at each of `voltages`;
    `kind` ("population", "mixture") goes into the folder's record."""

    kind, noun, results_file = "line", "grain", PARTICLES

    def __init__(self, kind: str, line: Line, n: int, seed: int, t_end: float, voltages,
                 fmu=None, separator_fmu=None, *, figure: bool = True):
        self.line_kind, self.line, self.n, self.seed, self.t_end = kind, line, n, seed, t_end
        self.voltages = [float(v) for v in voltages]
        self.fmu, self.separator_fmu, self.figure = fmu, separator_fmu, figure
        self.keys = []

    def prepare(self) -> None:
        self.line.check()
        check_count(len(self.voltages), "the number of voltages")
        if isinstance(self.n, int):
            check_count(self.n * len(self.voltages), f"separator runs of {self.n} grains at "
                                                     f"{len(self.voltages)} voltages")
        self.images = load_images(self.fmu, self.separator_fmu, self.line.separator, self.voltages)
        self.specs = line_specs(self.line, self.n, self.seed, self.t_end, self.images.models,
                                self.images.chute.model_description())
        check_line(self.line, self.specs, self.images)
        self.sha256 = self.images.sha256
        self.keys = keys_of(self.specs, self.images)

    def setup(self) -> dict:
        return {"kind": self.line_kind,
                **line_setup(self.line, self.n, self.seed, self.t_end, self.voltages)}

    def describe(self, out: str, executor) -> str:
        return (f"line: {self.n} grains of {' + '.join(self.line.particles)} on {self.line.wall} "
                f"(seed {self.seed}) at {len(self.voltages)} voltage(s) into {out}")

    def run(self, out: str, executor, *, progress: bool, max_runs: int | None) -> LineReport:
        return run_line(self.line, self.n, self.seed, self.t_end, self.images, out, executor,
                        specs=self.specs, progress=progress, figure=self.figure,
                        max_runs=max_runs)


def n_bins_of(images: LineImages) -> int:
    md = images.separator.model_description()
    return int(next(v.start for v in md.modelVariables if v.name == "n_bins"))


def collect_landings(results: pd.DataFrame, landings_dir: str) -> pd.DataFrame:
    """Every grain's landings (landings/<key>.csv), a row per grain and voltage, each led by
    the grain's key, particle, mass, exited and end_reason (NaN where its row has none)."""
    landings, lengths = read_many_series(landings_dir, list(results[KEY]))
    grain = np.repeat(np.arange(len(results)), lengths)
    head = {KEY: results[KEY].to_numpy()[grain], "particle": results["particle"].to_numpy()[grain],
            "mass": results["mass"].to_numpy()[grain],
            "exited": results["exited"].to_numpy().astype(np.int64)[grain],
            "end_reason": (results["end_reason"].to_numpy()[grain] if "end_reason" in results
                           else np.full(len(grain), np.nan))}
    return pd.concat([pd.DataFrame(head), landings], axis=1)


# the regions of a grain that did not leave the chute: at rest on it, on it at the horizon
# (or, where its row does not say which, only that it did not leave)
STAYED_REGIONS = ("at_rest", "at_horizon", "not_exited")
REGIONS = ("left", "right", "plate_neg", "plate_pos", "airborne") + STAYED_REGIONS


def region_of(landings: pd.DataFrame, splitter: float) -> pd.Series:
    """Each landing's region: "at_rest" (on the chute, its run ended at rest), "at_horizon"
    (still on the chute at its horizon), "not_exited" (did not leave, the row does not say
    why), "airborne", "plate_neg" (the plate at -gap/2), "plate_pos", "left" (landed at
    x_end < splitter) or "right"."""
    reason = landings["end_reason"] if "end_reason" in landings.columns \
        else pd.Series(np.nan, index=landings.index)
    stayed = np.where(reason == END_AT_REST, "at_rest",
                      np.where(reason.notna(), "at_horizon", "not_exited"))
    region = np.where(landings["exited"] == 0, stayed,
                      np.where(landings["electrode"] == -1, "plate_neg",
                               np.where(landings["electrode"] == 1, "plate_pos",
                                        np.where(landings["landed"] == 0, "airborne",
                                                 np.where(landings["x_end"] < splitter, "left",
                                                          "right")))))
    return pd.Series(region, index=landings.index)


def tally(landings: pd.DataFrame, line: Line, n_bins: int) -> tuple[pd.DataFrame, pd.DataFrame]:
    """(line.csv's table, bins.csv's): masses per voltage, region and material, and a
    mixture's grade and recovery of each product."""
    landings = landings.assign(region=region_of(landings, line.splitter))
    materials = [material(p, "particle").key for p in line.particles]
    rows, bin_rows = [], []
    for voltage, at in landings.groupby("voltage", sort=True):
        row = {"voltage": voltage}
        mass = {m: at[at["particle"] == m] for m in materials}
        for m in materials:
            g = mass[m]
            fed = g["mass"].sum()
            by_region = g.groupby("region")["mass"].sum()
            row[f"fed_{m}"] = fed
            n_by_region = g.groupby("region").size()
            row[f"n_fed_{m}"] = int(len(g))
            for region in REGIONS:
                row[f"{region}_{m}"] = float(by_region.get(region, 0.0))
            # not_exited: every grain that stayed on the chute, whatever its row says of why
            row[f"not_exited_{m}"] = sum(row[f"{r}_{m}"] for r in STAYED_REGIONS)
            for region in ("at_rest", "at_horizon"):
                row[f"n_{region}_{m}"] = int(n_by_region.get(region, 0))
            row[f"neg_side_{m}"] = row[f"left_{m}"] + row[f"plate_neg_{m}"]
            row[f"pos_side_{m}"] = row[f"right_{m}"] + row[f"plate_pos_{m}"]
            for b in range(1, n_bins + 1):
                bin_rows.append({"voltage": voltage, "bin": b, "particle": m,
                                 "mass": float(g.loc[(g["landed"] == 1) & (g["bin"] == b),
                                                     "mass"].sum())})
        if len(materials) == 2:
            positive = [m for m in materials if line.sigma0(m) > 0][0]
            for m in materials:
                # U > 0: a positive grain drifts to -x, into the negative-x side's product
                side = "neg_side" if (m == positive) == (voltage > 0) else "pos_side"
                product = sum(row[f"{side}_{k}"] for k in materials)
                row[f"product_{m}_side"] = -1 if side == "neg_side" else 1
                row[f"product_{m}_mass"] = product
                row[f"grade_{m}"] = row[f"{side}_{m}"] / product if product > 0 else math.nan
                # a material that drew no grain has no recovery (not a 0/0 warning)
                row[f"recovery_{m}"] = (row[f"{side}_{m}"] / row[f"fed_{m}"]
                                        if row[f"fed_{m}"] > 0 else math.nan)
            # how far from no separation: a random split of the feed recovers each material
            # in the share of the mass its product takes, so the two recoveries sum to 1 (its
            # grades are the feed's shares); a complete one recovers both whole: 1
            row["separation"] = sum(row[f"recovery_{m}"] for m in materials) - 1.0
        rows.append(row)
    return pd.DataFrame(rows), pd.DataFrame(bin_rows)


def stayed_text(row, materials, horizon: float | None = None, sep: str = "; ") -> str:
    """Per material of a line.csv row, how many grains stayed on the chute, by why, and
    their share of its fed mass: they never enter the separator."""
    at = f" of {horizon:g} s" if horizon is not None else ""
    parts = []
    for m in materials:
        fed = row[f"fed_{m}"]

        def share(region):
            return f" ({100 * row[f'{region}_{m}'] / fed:.3g} % of its mass)" if fed > 0 else ""

        text = (f"{m}: {int(row[f'n_fed_{m}'])} grains fed, {int(row[f'n_at_rest_{m}'])} at rest "
                f"on the chute{share('at_rest')}, {int(row[f'n_at_horizon_{m}'])} still on it "
                f"at the horizon{at}{share('at_horizon')}")
        if row[f"not_exited_{m}"] > row[f"at_rest_{m}"] + row[f"at_horizon_{m}"]:
            text += f", others did not leave it{share('not_exited')}"
        parts.append(text)
    return sep.join(parts)
