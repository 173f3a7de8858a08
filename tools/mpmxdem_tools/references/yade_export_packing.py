"""Writes a periodic YADE packing with YADE's own text export, as a YADE user would (YADE's
exports are readable by mpmxdem), then adds the periodic cell, which yade.export.text does not
write, as '# CELL' / '# HSIZE' comment lines after its '#format x_y_z_r' line: the file stays a
YADE text file (ymport.text skips comments) and becomes an mpmxdem [dem.sample] packing file.

  yade -n -x tools/mpmxdem_tools/references/yade_export_packing.py OUT.txt [N] [--raw RAW.txt]     (Debian package yade)

N spheres (default 30; radius 0.1 mm +/- 30 %) in a periodic cube of 1 mm (a loose cloud, as
pack.SpherePack.makeCloud places it; mpmxdem's [dem.sample] compacts it). --raw also keeps the
export exactly as YADE wrote it (no cell: mpmxdem refuses it and says what is missing).
"""
import sys

from yade import export, pack

args = sys.argv[1:]
raw = None
if "--raw" in args:
    i = args.index("--raw")
    raw = args[i + 1]
    del args[i:i + 2]
out = args[0]
n = int(args[1]) if len(args) > 1 else 30
size = 1e-3

O.periodic = True
O.cell.hSize = Matrix3(size, 0, 0, 0, size, 0, 0, 0, size)
sp = pack.SpherePack()
sp.makeCloud((0, 0, 0), (size, size, size), rMean=1e-4, rRelFuzz=0.3, num=n, periodic=True,
             seed=1)
sp.toSimulation()
export.text(raw or out)  # "#format x_y_z_r", then one "x y z r" line per sphere
with open(raw or out) as f:
    lines = f.read().splitlines()
h = O.cell.hSize
cell = [f"# CELL {O.cell.size[0]!r} {O.cell.size[1]!r} {O.cell.size[2]!r}",
        "# HSIZE " + " ".join(repr(h[a, b]) for a in range(3) for b in range(3))]
with open(out, "w") as f:
    f.write("\n".join(lines[:1] + cell + lines[1:]) + "\n")
print(f"yade_export_packing: {len(lines) - 1} spheres, cell {O.cell.size} m -> {out}"
      + (f" (YADE's export as it is: {raw})" if raw else ""))
