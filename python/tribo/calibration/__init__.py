"""Measurements and the model: the observables that calibrate and check its charging
(docs/model.md section 8d) and the calibration of a pair's charging parameters against
measured data (docs/calibration.md).

    observables  a single impact (Delta q, A_max), repeated impacts on fresh wall spots, a
                 chute's exit stream (mass-weighted q/m, its spread, the mass that stays);
                 batches of short runs in one FMU instance
"""
