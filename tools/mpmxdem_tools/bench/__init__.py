"""Benchmarks: speed against error, printed as figures; never tests."""
