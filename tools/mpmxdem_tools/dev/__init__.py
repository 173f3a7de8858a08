"""Set-up and development: running the jobs as their headers say, the index of the tools."""
