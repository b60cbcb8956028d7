"""What a feed draws (feed.py): the SI FMU's parameters it takes a distribution of, their
units, and the reference case's feed and chute. A module of constants alone, so that the
commands' options (tribo/cli) are made without loading the jobs' libraries."""

# the SI FMU's parameters a feed draws, by the package's names (fmu/names.py)
FEED_VARIABLES = ("epsilon", "size", "phi0_deg", "omega0", "drop_height", "drop_speed",
                  "drop_angle_deg")
FEED_UNITS = {"epsilon": "b/a", "size": "the long diameter 2a, m", "phi0_deg": "degrees",
              "omega0": "rad/s", "drop_height": "m", "drop_speed": "m/s",
              "drop_angle_deg": "degrees from the vertical, + down-slope"}
# the SI reference case's feed (README, docs/reference_case.md): shapes 0.3-1, sizes
# 0.2-2 mm, random orientation, dropped from 10 mm at rest onto 0.3 m of steel at 30 degrees
DEFAULT_DISTRIBUTIONS = {"epsilon": "uniform:0.3:1", "size": "uniform:2e-4:2e-3",
                         "phi0_deg": "uniform:0:180", "omega0": 0.0, "drop_height": 0.01,
                         "drop_speed": 0.0, "drop_angle_deg": 0.0}
DEFAULT_CHUTE = {"chute_length": 0.3, "tilt_deg": 30.0}
