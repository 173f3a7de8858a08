#!/usr/bin/python3
"""Renders the material points of an `mpmxdem run` (points.xmf, ParaView's default reader) to a
PNG: one panel per array, the points as spheres coloured by it, at one time step.

  xvfb-run -a tools/mpmxdem-tools render_points RUN_DIR OUT.png
      [--arrays q,displacement:Z] [--step -1] [--size 1400x900] [--title TEXT] [--radius 0.1]

--arrays: comma-separated point arrays of points.xmf (p, q, void_ratio, z, volume, stress,
velocity, displacement, F); NAME:X|Y|Z|Magnitude picks a component of a vector. --step: the
row (time step) index, negative from the end. Needs python3-paraview (Debian 12: paraview 5.11)
and, without a display, xvfb-run. docs/figures/points_geostatic_column.png was made with it
(docs/reference/outputs.md).
"""

import argparse
import os
import sys

TITLES = {"p": "p [Pa]", "q": "q [Pa]", "void_ratio": "void ratio [-]", "z": "Z [-]",
          "volume": "volume [m^3]", "velocity": "velocity [m/s]",
          "displacement": "displacement [m]", "F": "F [-]", "stress": "stress [Pa]"}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run")
    ap.add_argument("png")
    ap.add_argument("--arrays", default="q,displacement:Z")
    ap.add_argument("--step", type=int, default=-1)
    ap.add_argument("--size", default="1400x900")
    ap.add_argument("--title", default="")
    ap.add_argument("--radius", type=float, default=0.1, help="sphere radius of a point [m]")
    a = ap.parse_args()
    xmf = os.path.join(a.run, "points.xmf")
    if not os.path.exists(xmf):
        sys.exit(f"render_points: {xmf} is missing (an mpmxdem run directory?)")
    from paraview import simple

    reader = simple.OpenDataFile(xmf)  # Xdmf3 reader: ParaView's default for .xmf
    times = list(reader.TimestepValues)
    if not times:
        sys.exit(f"render_points: {xmf} has no time step")
    t = times[a.step]
    w, h = (int(v) for v in a.size.split("x"))
    arrays = [s.split(":") for s in a.arrays.split(",")]
    reader.UpdatePipeline(t)
    layout = simple.CreateLayout("points")
    layout.SetSize(w, h)
    # Side by side: location 0 split into len(arrays) equal cells (binary-tree locations).
    locs = []
    loc = 0
    for i in range(len(arrays) - 1):
        layout.SplitHorizontal(loc, 1.0 / (len(arrays) - i))
        locs.append(2 * loc + 1)
        loc = 2 * loc + 2
    locs.append(loc)
    views = []
    for i, spec in enumerate(arrays):
        name = spec[0]
        comp = spec[1] if len(spec) > 1 else None
        view = simple.CreateView("RenderView")
        simple.AssignViewToLayout(view=view, layout=layout, hint=locs[i])
        view.ViewTime = t
        view.OrientationAxesVisibility = 1
        view.Background = [1, 1, 1]
        try:
            view.UseColorPaletteForBackground = 0
        except AttributeError:
            pass
        d = simple.Show(reader, view)
        # Point Gaussian as shaded spheres (the "Points" representation with spheres draws nothing
        # under xvfb's software OpenGL here).
        d.SetRepresentationType("Point Gaussian")
        d.ShaderPreset = "Sphere"
        d.GaussianRadius = a.radius
        simple.ColorBy(d, ("POINTS", name, comp) if comp else ("POINTS", name))
        lut = simple.GetColorTransferFunction(name)
        if comp:
            lut.VectorMode = "Magnitude" if comp == "Magnitude" else "Component"
            if comp != "Magnitude":
                lut.VectorComponent = "XYZ".index(comp)
        d.RescaleTransferFunctionToDataRange(False, True)
        lut.ApplyPreset("Viridis (matplotlib)", True)
        d.SetScalarBarVisibility(view, True)
        bar = simple.GetScalarBar(lut, view)
        title = TITLES.get(name, name)
        bar.Title = title.replace(" [", f" {comp} [", 1) if comp else title
        bar.ComponentTitle = ""
        bar.TitleColor = bar.LabelColor = [0, 0, 0]
        bar.RangeLabelFormat = "%-#.3g"
        bar.TitleFontSize = 8
        bar.LabelFontSize = 7
        bar.ScalarBarLength = 0.5
        # Parallel projection from the front-left, up = +z, the whole sample with a margin.
        b = reader.GetDataInformation().GetBounds()
        c = [0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])]
        size = max(b[1] - b[0], b[3] - b[2], b[5] - b[4]) + 4 * a.radius
        view.CameraParallelProjection = 1
        # The focal point moved to the screen's right (3, -2, 0)/sqrt(13): the points on the left,
        # the colour bar on the right.
        c = [c[0] + 0.2 * size * 3 / 13**0.5, c[1] - 0.2 * size * 2 / 13**0.5, c[2]]
        view.CameraFocalPoint = c
        view.CameraPosition = [c[0] - 2 * size, c[1] - 3 * size, c[2] + size]
        view.CameraViewUp = [0, 0, 1]
        view.CameraParallelScale = 0.6 * size
        bar.WindowLocation = "Any Location"
        bar.Position = [0.62, 0.1]
        text = simple.Text(Text=(a.title + "\n" if a.title and i == 0 else "")
                           + f"{name}{' ' + comp if comp else ''}, t = {t:.4g} s")
        td = simple.Show(text, view)
        td.Color = [0, 0, 0]
        td.FontSize = 7
        td.WindowLocation = "Upper Left Corner"
        views.append(view)
    simple.SaveScreenshot(a.png, layout, ImageResolution=[w, h])
    print(f"render_points: {a.png}: {len(views)} panel(s) at t = {t:.6g} s ({len(times)} steps)")


if __name__ == "__main__":
    main()
