"""The paper's parameter study and parameter sweeps, driven through the tribo FMU.

Modules, one responsibility each:

    specs       what one run is (FMU parameters, horizon, recording interval) and its key
    fmu_run     one run of the FMU with fmpy: the recorded time series and its summary row
    summary     what a time series is summarised into (bounce envelope, charges, modes)
    results     the results CSV: append a row per finished run, resume, final order
    executors   where runs execute: serially here, or on Dask (local cluster or address)
    sweep       a sweep: skip finished runs, run the rest, record them as they finish
    transition  the transition roundness eps_t: coarse grid, then multi-section
    paper       the paper's study (docs/model.md section 7): runs, eps_t, figures, tables
    figures     the study's plots
    tables      the study's tables (CSV and markdown)

The command-line entries are examples/paper_study.py and examples/sweep.py.
"""
