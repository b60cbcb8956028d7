"""The runs a package command makes, as bench/runs_core.c's feed: one line a run, its horizon
and the SI front end's settings (the FMU's names and units), and for a line's grain its
separator's settings after `|`; the line's voltages are printed to stderr's last line
(`voltages v1,v2,...`), for runs_core's second argument.

    .venv/bin/python bench/runs_feed.py impact-map --speed 0.5,2,8 ... > feed.txt
    .venv/bin/python bench/runs_feed.py line sweep -n 100 --voltages 5e3:40e3:4 ... > feed.txt
    .venv/bin/python bench/runs_feed.py calibrate --impacts I.csv --chutes C.csv ... > feed.txt

The arguments are the command's (`tribo COMMAND ...`), parsed by the package's parser and made
into the command's job, so that the feed holds the runs the command makes: an impact map's
episodes and a line's grains as the job prepares them; a calibration's runs are those its fit
asks for, which depend on the fit's path: the calibration is run here, serially, and every
run it makes recorded (the package's `calibration.observables._chain`, wrapped)."""

import contextlib
import os
import sys
import tempfile

from tribo.cli.main import parser, subcommand
from tribo.fmu.names import to_fmu


def settings_text(params: dict) -> str:
    return " ".join(f"{k}={float(v)!r}" for k, v in params.items())


def impact_map(job) -> list[str]:
    md = job.image.model_description()
    return [f"{spec.t_end!r} tstar {settings_text(to_fmu(md, spec.params))}" for spec in job.specs]


def line(job) -> list[str]:
    from tribo.line.grain import chute_params_of, separator_parameters
    images = job.images
    chute_md = images.chute.model_description()
    separator_md = images.separator.model_description()
    out = []
    for spec in job.specs:
        params = chute_params_of(spec.params)
        separator = separator_parameters(params, images.settings, 0.0)
        separator.pop("voltage")
        separator["x_entry"] = float(spec.params["x_entry"])
        out.append(f"{spec.t_end!r} s {settings_text(to_fmu(chute_md, params))} | "
                   f"{settings_text(to_fmu(separator_md, separator))}")
    print(f"voltages {','.join(repr(v) for v in images.voltages)}", file=sys.stderr)
    return out


def calibrate(job) -> list[str]:
    from tribo.batch.executors import SerialExecutor
    from tribo.calibration import observables
    md = job.image.model_description()
    made = []
    chain = observables._chain

    def recorded(instance, md_, params, runs, outputs):
        # a fit's runs are single (repeat 1): the initial density is the run's own
        unit = "tstar" if runs.in_t_star else "s"
        made.append(f"{runs.horizon!r} {unit} {settings_text(to_fmu(md, params))}")
        return chain(instance, md_, params, runs, outputs)

    observables._chain = recorded
    try:
        with tempfile.TemporaryDirectory() as out, SerialExecutor() as executor:
            job.run(os.path.join(out, "calibration"), executor, progress=False, max_runs=None)
    finally:
        observables._chain = chain
    return made


def main(argv):
    args = parser(argv).parse_args(argv)
    job = subcommand(argv[0]).job_of(args)
    with contextlib.redirect_stdout(sys.stderr):
        job.prepare()
    kinds = {"impact-map": impact_map, "line": line, "calibrate": calibrate}
    print("\n".join(kinds[argv[0]](job)))


if __name__ == "__main__":
    main(sys.argv[1:])
