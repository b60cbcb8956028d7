"""Measurements and the model: the observables that calibrate and check its charging
(docs/model.md section 8d) and the calibration of a pair's charging parameters against
measured data (docs/calibration.md).

    observables  a single impact (Delta q, A_max), repeated impacts on fresh wall spots, a
                 chute's exit stream (mass-weighted q/m, its spread, the mass that stays);
                 batches of short runs in one FMU instance
    columns      the measured data's CSV files' columns: units, ranges, defaults
    data         the measured data's CSV files (impacts, chute runs) read and checked
    fit          the fit: sigma0 and whichever of charging_time and eta the data determine,
                 uncertainties, what the data do not determine
    plot         the figure of data against model
    runner       a calibration into an output folder (the package's job flow): the fit,
                 the points, the figure and the materials file it writes
"""
