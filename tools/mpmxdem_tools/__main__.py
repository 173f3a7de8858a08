"""`python3 -m mpmxdem_tools` (with tools/ on the path): the same as tools/mpmxdem-tools."""
import sys

from .cli import main

sys.exit(main(sys.argv[1:]))
