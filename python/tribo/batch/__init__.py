"""Many runs of the FMU, each keyed, recorded as it finishes and resumable: the machinery of
parameter sweeps, which the study, populations and impact maps run on too.

    specs      what one run is (parameters, horizon, recording interval) and its key
    grid       the runs of a sweep: combinations of values over a base set-up (the paper's);
               the sweep as a job
    run        one run of the FMU: its outputs at the times asked, or at its end (numpy
               and fmpy only: what a Dask worker process imports)
    particle   one particle's run: series, segment charges, summary row
    summary    what a time series is summarised into (bounce envelope, charges, motion classes)
    results    the results CSV: append a row per finished run, resume, backups
    executors  where runs execute: serially here, or on Dask (a local cluster of threads or
               processes, or an address)
    folder     an output folder: one command's results of one set-up, its record and lock
    sweep      a sweep: skip finished runs, run the rest, record them as they finish
    job        the one flow every job into an output folder takes (the API's and the
               command's): prepare, claim the folder, run, report
    plot       a sweep's figure
"""
