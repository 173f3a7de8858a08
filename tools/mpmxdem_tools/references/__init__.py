"""Pure-DEM references with YADE (scripts run by `yade -x`) and what reads their outputs."""
