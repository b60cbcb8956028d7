"""The console commands (entry points in pyproject.toml): tribo-study, tribo-sweep,
tribo-population and tribo-impact-map; `common` holds what they share."""
