#!/usr/bin/python3
"""Every Python script of tools/ starts: its imports resolve and it prints its usage.

Runs `python3 tools/NAME.py --help` for each script that parses its options with argparse (exit 0
and a "usage:" line, nothing written) and the own smoke mode of the others (scaling_model.py
--doc-table, tools_index.py). The YADE scripts (kind "pure-DEM references" in
tools/tools_index.py) run inside yade, not python3, and are left out. A script that no longer
imports (a renamed helper, a module that moved) fails here instead of in a user's hands.

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
OWN_MODE = {"scaling_model.py": ["--doc-table"], "tools_index.py": [], "band_fit.py": ["--self-test"]}


def main(root):
    sys.path.insert(0, os.path.join(root, "tools"))
    import tools_index  # noqa: E402 (the kinds of the scripts)

    yade = {n for n, k in tools_index.KIND.items() if tools_index.KINDS[k].startswith("pure-DEM")}
    names = sorted(n for n in os.listdir(os.path.join(root, "tools"))
                   if n.endswith(".py") and n not in yade)
    fails, skipped = [], []
    for name in names:
        args = OWN_MODE.get(name, ["--help"])
        r = subprocess.run([sys.executable, os.path.join("tools", name)] + args, cwd=root,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=300)
        ok = r.returncode == 0 or (name == "band_fit.py" and r.returncode == 77)  # 77: no numpy
        if ok and args == ["--help"] and "usage:" not in r.stdout:
            ok = False
        missing = re.search(r"ModuleNotFoundError: No module named '([^'.]+)", r.stdout)
        if not ok and missing and missing.group(1) in OPTIONAL:
            skipped.append(f"{name} (needs {missing.group(1)})")
            continue
        if not ok:
            fails.append(name)
            print(f"tools/{name} {' '.join(args)}: exit {r.returncode}\n{r.stdout[-2000:]}", file=sys.stderr)
    print(f"{len(names) - len(fails) - len(skipped)} of {len(names)} scripts of tools/ start, "
          f"{len(fails)} fail, {len(skipped)} skipped for a Python package not installed"
          f"{': ' + ', '.join(skipped) if skipped else ''} ({len(yade)} YADE scripts left out)")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
