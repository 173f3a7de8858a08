#!/usr/bin/env python3
"""Every relative link in README.md and docs/**/*.md resolves to a file (anchors are not checked).

Usage: check_links.py [REPO_ROOT]   (default: two levels above this file). Exit 1 naming each
broken link as FILE:LINE: TARGET.
"""
import os
import re
import sys

LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")


def markdown_files(root):
    yield os.path.join(root, "README.md")
    for base, dirs, files in os.walk(os.path.join(root, "docs")):
        dirs[:] = [d for d in dirs if d != "data"]
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(base, name)


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                           os.path.join(os.path.dirname(__file__), "..", ".."))
    broken, checked = [], 0
    for path in markdown_files(root):
        in_code = False
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, 1):
                if line.lstrip().startswith("```"):
                    in_code = not in_code
                if in_code:
                    continue
                for target in LINK.findall(line):
                    if "://" in target or target.startswith(("#", "mailto:")):
                        continue
                    checked += 1
                    file_part = target.split("#", 1)[0]
                    resolved = os.path.normpath(os.path.join(os.path.dirname(path), file_part))
                    if not os.path.exists(resolved):
                        broken.append(f"{os.path.relpath(path, root)}:{number}: {target}")
    for b in broken:
        print("broken link:", b)
    print(f"{checked} links checked, {len(broken)} broken")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
