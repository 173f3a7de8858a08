"""What the tools are: each with its kind (its subpackage, or for the shell scripts beside the
package, the table below) and the first sentence of its own description (docstring, first comment
block, or a folder's README.md title)."""
import ast
import os

from .paths import ROOT

TOOLS = os.path.join(ROOT, "tools")
PACKAGE = os.path.join(TOOLS, "mpmxdem_tools")

# The subpackages in the order of the index, each with the kind it holds.
SUBPACKAGES = [("dev", "set-up and development"), ("jobs", "job writers"),
               ("analysis", "analysis and figures"), ("references", "pure-DEM references (YADE)"),
               ("checks", "output checks"), ("bench", "benchmarks (never tests)")]
# The shell tools beside the package (tools/NAME), by subpackage whose kind they share.
SHELL = {"dev": "dev", "device": "dev", "node_bundle.sh": "dev", "regress": "dev", "bench_node.sh": "bench"}


def first_sentence(paragraph_lines):
    """The first sentence of a paragraph given as lines (joined; cut after the first '. ')."""
    text = " ".join(line.strip() for line in paragraph_lines).strip()
    cut = text.find(". ")
    return text[: cut + 1] if cut >= 0 else text


def first_line(path):
    """The first sentence of a Python docstring, of a shell script's first comment block, or a
    directory's README.md title."""
    if os.path.isdir(path):
        readme = os.path.join(path, "README.md")
        if os.path.exists(readme):
            for line in open(readme, encoding="utf-8"):
                if line.strip():
                    return line.strip().lstrip("#").strip()
        return ""
    text = open(path, encoding="utf-8").read()
    if path.endswith(".py"):
        doc = (ast.get_docstring(ast.parse(text)) or "").strip()
        return first_sentence(doc.split("\n\n")[0].split("\n"))
    block = []
    for line in text.split("\n")[1:]:
        body = line.lstrip("#").strip() if line.startswith("#") else None
        if body:
            block.append(body)
        elif block:
            break
    return first_sentence(block)


def modules(sub):
    """The tools of a subpackage: (name, path) of each module but __init__."""
    folder = os.path.join(PACKAGE, sub)
    names = sorted(n[:-3] for n in os.listdir(folder) if n.endswith(".py") and not n.startswith("__"))
    return [(n, os.path.join(folder, n + ".py")) for n in names]


def find(name):
    """(subpackage, path) of the tool NAME, or None."""
    for sub, _ in SUBPACKAGES:
        path = os.path.join(PACKAGE, sub, name + ".py")
        if not name.startswith("_") and os.path.isfile(path):
            return sub, path
    return None


def runs_in_yade(path):
    """True for a script run with `yade -x`, not python3: it imports yade, or its docstring's
    usage is `yade ... -x tools/mpmxdem_tools/references/NAME.py` (YADE's own globals, no import)."""
    text = open(path, encoding="utf-8").read()
    rel = "tools/mpmxdem_tools/" + os.path.relpath(path, PACKAGE).replace(os.sep, "/")
    if f"-x {rel}" in (ast.get_docstring(ast.parse(text)) or ""):
        return True
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, ast.ImportFrom) and (node.module or "").split(".")[0] == "yade":
            return True
        if isinstance(node, ast.Import) and any(a.name.split(".")[0] == "yade" for a in node.names):
            return True
    return False


def command(sub, name, path):
    """How a user runs a tool."""
    if runs_in_yade(path):
        return f"tools/mpmxdem_tools/{sub}/{name}.py"
    return f"tools/mpmxdem-tools {name}"


def entries():
    """(kind index, what a user types, path) of every tool, in the index's order."""
    rows = []
    for k, (sub, _) in enumerate(SUBPACKAGES):
        for name, path in modules(sub):
            rows.append((k, command(sub, name, path), path))
        for name, owner in sorted(SHELL.items()):
            if owner == sub:
                shown = "tools/" + name + ("/" if os.path.isdir(os.path.join(TOOLS, name)) else "")
                rows.append((k, shown, os.path.join(TOOLS, name)))
    return rows


def problems():
    """What keeps the index from being whole: a tool without a description, a file beside the
    package that is not in SHELL, a SHELL entry that does not exist."""
    out = []
    for _, shown, path in entries():
        if not os.path.exists(path):
            out.append(f"{shown}: named in mpmxdem_tools/index.py (SHELL) but does not exist")
        elif not first_line(path):
            out.append(f"{shown}: no first sentence of description (docstring, comment or README)")
    for n in sorted(os.listdir(TOOLS)):
        if n.startswith((".", "__")) or n in ("mpmxdem_tools", "mpmxdem-tools") or n in SHELL:
            continue
        out.append(f"tools/{n}: neither a module of the package nor a shell tool named in "
                   "mpmxdem_tools/index.py (SHELL)")
    return out


def markdown_table():
    lines = ["| kind | tool | what it does |", "|---|---|---|"]
    for k, shown, path in entries():
        what = first_line(path).replace("|", "\\|") if os.path.exists(path) else ""
        lines.append(f"| {SUBPACKAGES[k][1]} | `{shown}` | {what} |")
    return "\n".join(lines)


def text_index():
    """The index for a terminal: each kind, then its tools with the first sentence, cut short."""
    out = []
    for k, (sub, kind) in enumerate(SUBPACKAGES):
        out.append(f"{kind} ({sub}):")
        for kk, shown, path in entries():
            if kk != k:
                continue
            name = shown.replace("tools/mpmxdem-tools ", "")
            what = first_line(path) if os.path.exists(path) else ""
            if len(what) > 78:
                what = what[:75].rstrip() + "..."
            out.append(f"  {name:32s} {what}" if len(name) <= 32 else f"  {name}\n  {'':32s} {what}")
        out.append("")
    return "\n".join(out).rstrip()
