"""mpmxdem's Python tools: job writers, analysis and figures, pure-DEM references (YADE), output
checks and benchmarks, one module per tool.

Run a tool through the entry point beside this package, from the repository root:
`tools/mpmxdem-tools --help` lists them by kind, `tools/mpmxdem-tools NAME [ARGS]` runs one
(equivalently `PYTHONPATH=tools python3 -m mpmxdem_tools NAME [ARGS]`). The YADE scripts of
`references` run inside YADE: `yade -j1 -n -x tools/mpmxdem_tools/references/NAME.py [ARGS]`.
Shared code: `paths` (where the repository, the build and the tools are), `readers` (results.h5,
resolved jobs and run summaries).
"""
