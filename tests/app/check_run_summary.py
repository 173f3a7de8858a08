"""Checks a run's run_summary.json (docs/reference/outputs.md) against expected fields.

Usage: check_run_summary.py RUN_DIR KEY=VALUE [KEY=VALUE ...]
A VALUE is compared with the field as JSON writes it (an integer as digits, a string as is);
KEY~VALUE asks that the string field contain VALUE. Exit 1 naming the field on a mismatch;
prints "run_summary: ok" and the fields checked otherwise. Standard library only.
"""
import json
import os
import sys


def main(run_dir, checks):
    path = os.path.join(run_dir, "run_summary.json")
    with open(path) as f:
        s = json.load(f)
    if s.get("format") != "mpmxdem run summary" or s.get("format_version") != 1:
        sys.exit(f"{path}: format {s.get('format')!r} version {s.get('format_version')!r}")
    for c in checks:
        contains = "~" in c and ("=" not in c or c.index("~") < c.index("="))
        key, want = c.split("~" if contains else "=", 1)
        if key not in s:
            sys.exit(f"{path}: no field {key}")
        have = s[key]
        text = have if isinstance(have, str) else json.dumps(have)
        if (want not in text) if contains else (text != want):
            sys.exit(f"{path}: {key} = {text!r}, expected {'to contain ' if contains else ''}{want!r}")
    print(f"run_summary: ok ({', '.join(checks)})")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
