"""The entry point: `tools/mpmxdem-tools` lists the tools by kind; `tools/mpmxdem-tools NAME
[ARGS]` runs the tool NAME with ARGS, as if it were a script (its own `--help` gives its usage)."""
import os
import runpy
import sys

from . import index
from .paths import ROOT

USAGE = """usage: tools/mpmxdem-tools NAME [ARGS]    run a tool (NAME --help: its usage)
       tools/mpmxdem-tools --help             this list
       yade -j1 -n -x tools/mpmxdem_tools/references/NAME.py [ARGS]    a YADE script
"""


def main(argv):
    if not argv or argv[0] in ("-h", "--help", "help"):
        try:
            print(USAGE)
            print(index.text_index())
        except BrokenPipeError:  # `--help | head`
            sys.stdout = open(os.devnull, "w")
        return 0
    name = argv[0][:-3] if argv[0].endswith(".py") else argv[0]
    found = index.find(name)
    if found is None:
        print(f"tools/mpmxdem-tools: no tool named {name!r} (tools/mpmxdem-tools --help lists them)",
              file=sys.stderr)
        return 2
    sub, path = found
    if index.runs_in_yade(path):
        here = os.path.realpath(os.getcwd()) == os.path.realpath(ROOT)
        rel = os.path.relpath(path, ROOT) if here else path
        print(f"tools/mpmxdem-tools: {name} runs inside YADE: yade -j1 -n -x {rel} [ARGS]", file=sys.stderr)
        return 2
    # argparse names the program after sys.argv[0]: "mpmxdem-tools NAME" in every usage line
    # (alter_sys=False keeps it; runpy would put the module's file there).
    sys.argv = [f"mpmxdem-tools {name}"] + list(argv[1:])
    runpy.run_module(f"mpmxdem_tools.{sub}.{name}", run_name="__main__", alter_sys=False)
    return 0
