#!/usr/bin/python3
"""Renders a column collapse run (points.xmf, ParaView's default reader) seen along y (the plane
strain axis): one panel per time, the points as spheres coloured by one array.

  xvfb-run -a tools/mpmxdem-tools render_column_collapse RUN_DIR OUT.png
      [--array p] [--times 0,0.3,0.6,1.0] [--radius 0.02] [--range 0,20000] [--title TEXT]

--times: simulated times [s] (the nearest output row of each); --array: a point array of
points.xmf (p, q, z, void_ratio, velocity:Magnitude, ...). The colour range is the same on every
panel (--range, or the array's range over the chosen rows). Needs python3-paraview.
"""

import argparse
import os
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run")
    ap.add_argument("png")
    ap.add_argument("--array", default="p")
    ap.add_argument("--times", default="0,0.3,0.6,1.0")
    ap.add_argument("--radius", type=float, default=0.02)
    ap.add_argument("--range", default="")
    ap.add_argument("--title", default="")
    ap.add_argument("--width", type=int, default=700, help="pixels per panel")
    a = ap.parse_args()
    xmf = os.path.join(a.run, "points.xmf")
    if not os.path.exists(xmf):
        sys.exit(f"render_column_collapse: {xmf} is missing")
    from paraview import simple

    reader = simple.OpenDataFile(xmf)  # Xdmf3 reader: ParaView's default for .xmf
    steps = list(reader.TimestepValues)
    want = [float(s) for s in a.times.split(",")]
    times = [min(steps, key=lambda s: abs(s - w)) for w in want]
    name, comp = (a.array.split(":") + [""])[:2]
    glyph = simple.Glyph(Input=reader, GlyphType="Sphere")
    glyph.ScaleArray = ["POINTS", "No scale array"]
    glyph.ScaleFactor = 2 * a.radius
    glyph.GlyphMode = "All Points"
    if a.range:
        lo, hi = (float(v) for v in a.range.split(","))
    else:
        lo, hi = float("inf"), -float("inf")
        for t in times:
            reader.UpdatePipeline(t)
            r = reader.PointData[name].GetRange(-1 if comp == "Magnitude" else 0)
            lo, hi = min(lo, r[0]), max(hi, r[1])
    # The extent: the whole grid of the job is not known here; take the points' bounds over the rows.
    bx = [float("inf"), -float("inf"), float("inf"), -float("inf")]
    for t in times:
        reader.UpdatePipeline(t)
        b = reader.GetDataInformation().GetBounds()
        bx = [min(bx[0], b[0]), max(bx[1], b[1]), min(bx[2], b[4]), max(bx[3], b[5])]
    n = len(times)
    w = a.width
    ext_x, ext_z = bx[1] - bx[0] + 4 * a.radius, bx[3] - bx[2] + 4 * a.radius
    h = int(w * ext_z / ext_x) + 40
    lut = simple.GetColorTransferFunction(name)
    lut.ApplyPreset("Viridis (matplotlib)", True)
    if comp:
        lut.VectorMode = "Magnitude" if comp == "Magnitude" else "Component"
        lut.VectorComponent = {"X": 0, "Y": 1, "Z": 2}.get(comp, 0)
    lut.RescaleTransferFunction(lo, hi)
    lut.AutomaticRescaleRangeMode = "Never"
    view = simple.CreateView("RenderView")
    view.ViewSize = [w, h]
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass
    d = simple.Show(glyph, view)
    simple.ColorBy(d, ("POINTS", name, comp) if comp else ("POINTS", name))
    cx, cz = 0.5 * (bx[0] + bx[1]), 0.5 * (bx[2] + bx[3])
    view.CameraParallelProjection = 1
    view.CameraFocalPoint = [cx, 0.0, cz]
    view.CameraPosition = [cx, -10.0, cz]
    view.CameraViewUp = [0, 0, 1]
    view.CameraParallelScale = 0.5 * max(ext_z + 40 * ext_x / w, ext_x * h / w)
    # One screenshot per time, put side by side (top to bottom) with matplotlib, one colour bar.
    import tempfile

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt

    tmp = tempfile.mkdtemp()
    fig, axs = plt.subplots(n, 1, figsize=(8, 8 * n * h / w / 1.0 + 0.6), squeeze=False)
    for i, t in enumerate(times):
        view.ViewTime = t
        f = os.path.join(tmp, f"{i}.png")
        simple.SaveScreenshot(f, view, ImageResolution=[w, h])
        axs[i, 0].imshow(mpimg.imread(f))
        axs[i, 0].set_axis_off()
        axs[i, 0].set_title((a.title + ": " if a.title and i == 0 else "") + f"t = {t:.3g} s",
                            fontsize=9, loc="left")
    sm = plt.cm.ScalarMappable(cmap="viridis", norm=plt.Normalize(lo, hi))
    fig.colorbar(sm, ax=axs[:, 0].tolist(), orientation="horizontal", fraction=0.04, pad=0.02,
                 label=f"{name} {comp}".strip() + (" [Pa]" if name in ("p", "q") else ""))
    fig.savefig(a.png, dpi=110, bbox_inches="tight")
    print(f"render_column_collapse: wrote {a.png} ({n} panels, {name} in [{lo:.4g}, {hi:.4g}])")


if __name__ == "__main__":
    main()
