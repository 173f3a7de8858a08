"""Analysis and figures: the manual's tables and figures from runs and stored data."""
