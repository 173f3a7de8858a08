#!/usr/bin/python3
"""The index of tools/: every script with its kind and the first line of its own description.

Prints the Markdown table of docs/reference/tools.md (a generated table: the suite checks that it
is what this prints, so a new script must be given a kind here and a first docstring line, or a
first comment line for a shell script). Standard library only.

Usage: /usr/bin/python3 tools/tools_index.py
"""
import ast
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TOOLS = os.path.join(ROOT, "tools")

KINDS = ["set-up and development", "job writers", "analysis and figures", "pure-DEM references (YADE)",
         "output checks", "benchmarks (never tests)"]
KIND = {
    "dev": 0, "device": 0, "node_bundle.sh": 0, "regress": 0, "run_jobs.py": 0, "tools_index.py": 0,
    "biaxial_make_jobs.py": 1, "footing_make_job.py": 1, "column_scale_job.py": 1,
    "band_fit.py": 2, "biaxial_analysis.py": 2, "biaxial_field_convergence.py": 2, "biaxial_compare.py": 2, "biaxial_dem_seeds.py": 2,
    "biaxial_j_maps.py": 2, "biaxial_paraview.py": 2, "biaxial_seed_mean.py": 2,
    "column_cell_stress.py": 2, "column_frictional_family.py": 2, "column_grain_scale.py": 2, "column_inertial_numbers.py": 2, "column_resolution_figure.py": 2,
    "footing_curves.py": 2, "footing_sparing_map.py": 2, "footing_family.py": 2, "bearing_capacity.py": 2,
    "footing_rve_maps.py": 2, "mpm_column_collapse.py": 2,
    "plot_column_collapse.py": 2, "plot_triaxial.py": 2, "render_column_collapse.py": 2,
    "render_points.py": 2, "render_rve.py": 2, "triaxial_errors.py": 2, "scaling_model.py": 2,
    "balance_table.py": 2, "dem_against_yade.py": 2, "rve_low_pressure_strength.py": 2,
    "yade_column_collapse.py": 3, "yade_column_collapse_partial.py": 3,
    "yade_export_packing.py": 3, "yade_read_packing.py": 3, "yade_hertz_mindlin_pair.py": 3,
    "yade_triax_hertz_mindlin.py": 3,
    "check_grain_vtk.py": 4, "check_outputs.py": 4,
    "bench_coupling.py": 5, "bench_dem_pairs.py": 5, "bench_dem_speedup.py": 5, "bench_node.sh": 5,
    "bench_sparing.py": 5, "bench_contact_laws.py": 5, "bench_speed_error.py": 5, "coupling_bias.py": 5,
}


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


def entries():
    names = sorted(n for n in os.listdir(TOOLS) if not n.startswith((".", "__")))
    return [(n, os.path.join(TOOLS, n)) for n in names]


def main():
    rows, fails = [], 0
    for name, path in entries():
        if name not in KIND:
            print(f"tools/{name}: no kind in tools/tools_index.py (KIND)", file=sys.stderr)
            fails += 1
            continue
        what = first_line(path)
        if not what:
            print(f"tools/{name}: no first line of description (docstring, comment or README)",
                  file=sys.stderr)
            fails += 1
            continue
        rows.append((KIND[name], name + ("/" if os.path.isdir(path) else ""), what.replace("|", "\\|")))
    missing = [n for n in KIND if not os.path.exists(os.path.join(TOOLS, n))]
    for n in missing:
        print(f"tools/tools_index.py names tools/{n}, which does not exist", file=sys.stderr)
        fails += 1
    print("| kind | tool | what it does |")
    print("|---|---|---|")
    for kind, name, what in sorted(rows):
        print(f"| {KINDS[kind]} | `tools/{name}` | {what} |")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
