"""Output checks: a run's outputs opened with the clients researchers use."""
