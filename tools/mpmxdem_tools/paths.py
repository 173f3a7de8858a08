"""Where things are: the repository root, the default build, and how one tool runs another."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LAUNCHER = os.path.join(ROOT, "tools", "mpmxdem-tools")
DATA = os.path.join(ROOT, "docs", "data")
MPMXDEM = os.path.join(ROOT, "build", "mpmxdem")


def tool_command(name):
    """The command line that runs the tool NAME (a module of this package) with this Python."""
    return [sys.executable, LAUNCHER, name]
