"""The impact jobs' defaults that the command line shows (tribo/cli): constants alone, so
that its options are made without loading the jobs' libraries."""

DEFAULT_LIMIT = 200.0  # contact periods' worth of t* before an episode counts as sustained
