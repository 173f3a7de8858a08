"""Opens an mpmxdem packing file with YADE's text import, as a YADE user would (our
packings readable by YADE as they are). Exit 0 when YADE reads every sphere line of the file.

  yade -n -x tools/mpmxdem_tools/references/yade_read_packing.py FILE       (Debian package yade)
"""
import sys

from yade import O, ymport

path = sys.argv[1]
spheres = ymport.text(path)
O.bodies.append(spheres)
expected = sum(1 for line in open(path) if line.strip() and not line.lstrip().startswith("#"))
print(f"YADE read {len(spheres)} spheres of {expected} sphere lines in {path}; first radius "
      f"{spheres[0].shape.radius if spheres else 'none'}")
sys.exit(0 if len(spheres) == expected and expected > 0 else 1)
