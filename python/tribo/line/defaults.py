"""The line's defaults that the command line shows (tribo/cli): constants alone, so that its
options are made without loading the jobs' libraries."""

DEFAULT_PAIR = ("PE", "nylon")  # on steel: sigma0 -1e-5 and +1e-5 C/m2 (materials.toml)
DEFAULT_WALL = "steel"
DEFAULT_FEED_WIDTH = 0.01  # m, the feed slot across the gap
