#!/usr/bin/python3
"""The points of a plane-strain biaxial run (points.xmf, ParaView's default Xdmf reader) seen
along the thickness (y), coloured by a few arrays, side by side in one PNG (docs/validation/biaxial.md).

  xvfb-run -a tools/mpmxdem-tools biaxial_paraview RUN_DIR OUT.png [--arrays q,void_ratio,z]
      [--step -1] [--radius 0.003]
"""
import argparse
import os
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run")
    ap.add_argument("png")
    ap.add_argument("--arrays", default="q,void_ratio,z")
    ap.add_argument("--step", type=int, default=-1)
    ap.add_argument("--radius", type=float, default=0.003, help="point sphere radius [m]")
    a = ap.parse_args()
    xmf = os.path.join(a.run, "points.xmf")
    if not os.path.exists(xmf):
        sys.exit(f"biaxial_paraview: {xmf} is missing")
    from paraview import simple

    reader = simple.OpenDataFile(xmf)
    t = list(reader.TimestepValues)[a.step]
    reader.UpdatePipeline(t)
    bounds = reader.GetDataInformation().GetBounds()
    cx, cz = 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[4] + bounds[5])
    size = max(bounds[1] - bounds[0], bounds[5] - bounds[4])
    names = a.arrays.split(",")
    tiles = []
    for name in names:
        view = simple.CreateView("RenderView")
        view.ViewSize = [500, 800]
        view.ViewTime = t
        view.OrientationAxesVisibility = 0
        view.Background = [1, 1, 1]
        try:  # ParaView 5.11: a single background colour needs this switch
            view.UseColorPaletteForBackground = 0
        except AttributeError:
            pass
        glyph = simple.Glyph(Input=reader, GlyphType="Sphere")
        glyph.ScaleArray = ["POINTS", "No scale array"]
        glyph.ScaleFactor = 2 * a.radius
        glyph.GlyphMode = "All Points"
        disp = simple.Show(glyph, view)
        simple.ColorBy(disp, ("POINTS", name))
        disp.RescaleTransferFunctionToDataRange(True, False)
        bar = simple.GetScalarBar(simple.GetColorTransferFunction(name), view)
        bar.Title = name
        bar.ComponentTitle = ""
        bar.TitleColor = [0, 0, 0]
        bar.LabelColor = [0, 0, 0]
        disp.SetScalarBarVisibility(view, True)
        view.CameraPosition = [cx, -10.0 * size, cz]
        view.CameraFocalPoint = [cx, 0.0, cz]
        view.CameraViewUp = [0, 0, 1]
        view.CameraParallelProjection = 1
        view.CameraParallelScale = 0.62 * size
        out = f"{a.png}.{name}.png"
        simple.SaveScreenshot(out, view, ImageResolution=[500, 800])
        tiles.append(out)
    from PIL import Image

    ims = [Image.open(p) for p in tiles]
    w = Image.new("RGB", (sum(i.width for i in ims), max(i.height for i in ims)), "white")
    x = 0
    for i in ims:
        w.paste(i, (x, 0))
        x += i.width
    w.save(a.png)
    for p in tiles:
        os.remove(p)
    print(f"biaxial_paraview: {a.png}: {len(names)} panel(s) at t = {t:.4g} s")


if __name__ == "__main__":
    main()
