"""The console commands (entry points in pyproject.toml): tribo-study, tribo-sweep."""
