#!/usr/bin/python3
"""The index of tools/: every tool with its kind and the first sentence of its own description.

Prints the Markdown table of docs/reference/tools.md (a generated table: the suite checks that it
is what this prints). A new tool is a module in the subpackage of its kind with a docstring whose
first sentence says what it does; a new shell script beside the package is named in
mpmxdem_tools/index.py (SHELL). Exit 1 when one of them is not. Standard library only.

Usage: tools/mpmxdem-tools tools_index
"""
import argparse
import sys

from .. import index


def main():
    argparse.ArgumentParser(description=__doc__.split("\n\n")[0]).parse_args()
    for p in index.problems():
        print(p, file=sys.stderr)
    print(index.markdown_table())
    return 1 if index.problems() else 0


if __name__ == "__main__":
    sys.exit(main())
