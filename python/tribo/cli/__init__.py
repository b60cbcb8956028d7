"""The command `tribo` (main.py), a subcommand per job: population, line, impact-map, sweep,
study; each a module here (add_arguments, run) listed in main.SUBCOMMANDS,
`common` for what they share. The names tribo-population, tribo-line, tribo-impact-map,
tribo-sweep and tribo-study stay as aliases (main.ALIASES)."""
