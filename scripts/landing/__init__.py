"""Landing frequencies of real objects against repose's predictions (scripts/experiments.py)."""
