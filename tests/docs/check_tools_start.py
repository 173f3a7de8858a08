#!/usr/bin/python3
"""Every Python script of tools/ starts: its imports resolve and it prints its usage.

Runs `tools/mpmxdem-tools NAME --help` for each tool of the package that parses its options with
argparse (exit 0 and a "usage:" line, nothing written) and the own smoke mode of the others
(scaling_model --doc-table, band_fit --self-test). The YADE scripts (those that import yade, see
tools/mpmxdem_tools/index.py) run inside yade, not python3, and are left out; the entry point
itself must print its index. A tool that no longer imports (a renamed helper, a module that moved)
fails here instead of in a user's hands.

Usage: /usr/bin/python3 tests/docs/check_tools_start.py REPO_ROOT
"""
import os
import re
import subprocess
import sys

# Debian packages that the figures and analyses need but the test command does not install
# (tools/dev installs python3-h5py only): a script that stops on one of these is skipped, not failed.
OPTIONAL = {"pandas", "matplotlib", "numpy", "scipy", "h5py", "paraview", "vtk"}
# Scripts without argparse, and the argument that runs them without side effects.
OWN_MODE = {"scaling_model": ["--doc-table"], "band_fit": ["--self-test"]}


def main(root):
    root = os.path.abspath(root)
    sys.path.insert(0, os.path.join(root, "tools"))
    from mpmxdem_tools import index  # noqa: E402 (the tools and their kinds)

    launcher = os.path.join(root, "tools", "mpmxdem-tools")
    tools = [(n, p) for sub, _ in index.SUBPACKAGES for n, p in index.modules(sub)]
    yade = {n for n, p in tools if index.runs_in_yade(p)}
    names = sorted(n for n, _ in tools if n not in yade)
    fails, skipped = [], []
    r = subprocess.run([sys.executable, launcher, "--help"], cwd=root, stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, text=True, timeout=300)
    if r.returncode != 0 or "usage: tools/mpmxdem-tools" not in r.stdout or "run_jobs" not in r.stdout:
        fails.append("the entry point")
        print(f"tools/mpmxdem-tools --help: exit {r.returncode}\n{r.stdout[-2000:]}", file=sys.stderr)
    for name in names:
        args = OWN_MODE.get(name, ["--help"])
        r = subprocess.run([sys.executable, launcher, name] + args, cwd=root,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
        ok = r.returncode == 0 or (name == "band_fit" and r.returncode == 77)  # 77: no numpy
        if ok and args == ["--help"] and "usage:" not in r.stdout:
            ok = False
        missing = re.search(r"ModuleNotFoundError: No module named '([^'.]+)", r.stdout)
        if not ok and missing and missing.group(1) in OPTIONAL:
            skipped.append(f"{name} (needs {missing.group(1)})")
            continue
        if not ok:
            fails.append(name)
            print(f"tools/mpmxdem-tools {name} {' '.join(args)}: exit {r.returncode}\n{r.stdout[-2000:]}", file=sys.stderr)
    print(f"{len(names) - len(fails) - len(skipped)} of {len(names)} tools start, "
          f"{len(fails)} fail, {len(skipped)} skipped for a Python package not installed"
          f"{': ' + ', '.join(skipped) if skipped else ''} ({len(yade)} YADE scripts left out)")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
