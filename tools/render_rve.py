#!/usr/bin/python3
"""Renders a grain-scale view written by `mpmxdem inspect CKPT --rve ID --vtk DIR` to a PNG with
ParaView (two panels: the spheres coloured by a sphere array, and the contact network as tubes
whose radius and colour follow the normal force; the periodic cell outlined in both).

  xvfb-run -a /usr/bin/python3 tools/render_rve.py DIR/rve_<id>_step_<step>.vtm OUT.png
      [--color radius|velocity|spin|contacts] [--size 1600x800] [--title TEXT] [--colors 256]

Needs python3-paraview (Debian 12: paraview 5.11) and, without a display, xvfb-run. The figure
in docs/figures/rve_grains.png was made with it (docs/dem.md, "Grain-scale views").
"""

import argparse
import os
import sys


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("vtm", help="rve_<id>_step_<step>.vtm written by mpmxdem inspect --vtk")
    ap.add_argument("png")
    ap.add_argument("--color", default="radius", choices=["radius", "velocity", "spin", "contacts"],
                    help="sphere array of the left panel (vectors: their magnitude)")
    ap.add_argument("--size", default="1600x800", help="image size in pixels, WxH")
    ap.add_argument("--title", default=None, help="text above the panels (default: the file name)")
    ap.add_argument("--colors", type=int, default=0,
                    help="reduce the PNG to this many colours with Pillow if installed (256: "
                         "about 4 times smaller; 0: keep true colour)")
    a = ap.parse_args()
    stem = a.vtm[:-len(".vtm")] if a.vtm.endswith(".vtm") else a.vtm
    files = {b: stem + suffix for b, suffix in
             (("spheres", "_spheres.vtp"), ("contacts", "_contacts.vtp"), ("cell", "_cell.vtu"))}
    for f in files.values():
        if not os.path.exists(f):
            sys.exit(f"render_rve: {f} is missing (write the view with mpmxdem inspect --vtk)")
    width, height = (int(v) for v in a.size.split("x"))

    from paraview import simple as pv
    from paraview import servermanager as sm

    spheres = pv.XMLPolyDataReader(FileName=[files["spheres"]])
    contacts = pv.XMLPolyDataReader(FileName=[files["contacts"]])
    cell = pv.XMLUnstructuredGridReader(FileName=[files["cell"]])
    sd = sm.Fetch(spheres)
    cd = sm.Fetch(contacts)
    n_spheres = sd.GetNumberOfPoints()
    n_contacts = cd.GetNumberOfCells()
    r_range = sd.GetPointData().GetArray("radius").GetRange()
    fn_range = cd.GetCellData().GetArray("normal_force").GetRange() if n_contacts else (0, 1)

    # Spheres: one sphere glyph per point, its true radius (the glyph source has radius 0.5).
    glyph = pv.Glyph(Input=spheres, GlyphType="Sphere")
    glyph.ScaleArray = ["POINTS", "radius"]
    glyph.ScaleFactor = 2.0
    glyph.GlyphMode = "All Points"
    glyph.GlyphType.ThetaResolution = 16
    glyph.GlyphType.PhiResolution = 12

    # Contacts: tubes of radius 0.03 .. 0.53 r_min growing with the normal force.
    c2p = pv.CellDatatoPointData(Input=contacts)
    c2p.PassCellData = 1
    tube_r = pv.Calculator(Input=c2p)
    tube_r.ResultArrayName = "tube_radius"
    span = max(fn_range[1], 1e-300)
    tube_r.Function = f"{r_range[0]} * (0.03 + 0.50 * normal_force / {span})"
    tube = pv.Tube(Input=tube_r)
    tube.Scalars = ["POINTS", "tube_radius"]
    tube.VaryRadius = "By Absolute Scalar"
    tube.NumberofSides = 10
    tube.Capping = 1

    outline = pv.Outline(Input=cell)

    layout = pv.CreateLayout("rve")
    left = pv.CreateView("RenderView")
    right = pv.CreateView("RenderView")
    pv.AssignViewToLayout(view=left, layout=layout, hint=0)
    pv.AssignViewToLayout(view=right, layout=layout, hint=0)
    layout.SetSize(width, height)
    for v in (left, right):
        v.OrientationAxesVisibility = 1
        v.Background = [1.0, 1.0, 1.0]
        try:
            v.UseColorPaletteForBackground = 0
        except AttributeError:
            pass

    gd = pv.Show(glyph, left)
    arr = {"radius": "radius", "velocity": "velocity", "spin": "spin",
           "contacts": "contacts"}[a.color]
    pv.ColorBy(gd, ("POINTS", arr, "Magnitude") if arr in ("velocity", "spin") else
               ("POINTS", arr))
    lut = pv.GetColorTransferFunction(arr)
    lut.ApplyPreset("Viridis (matplotlib)", True)
    gd.SetScalarBarVisibility(left, True)
    bar = pv.GetScalarBar(lut, left)
    bar.Title = {"radius": "radius [m]", "velocity": "|velocity| [m/s]", "spin": "|spin| [rad/s]",
                 "contacts": "contacts per sphere"}[a.color]
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.RangeLabelFormat = "%-#.3g"

    td = pv.Show(tube, right)
    pv.ColorBy(td, ("POINTS", "normal_force"))
    flut = pv.GetColorTransferFunction("normal_force")
    flut.ApplyPreset("Inferno (matplotlib)", True)
    flut.InvertTransferFunction()
    flut.RescaleTransferFunction(0.0, fn_range[1])
    td.SetScalarBarVisibility(right, True)
    fbar = pv.GetScalarBar(flut, right)
    fbar.Title = "normal force [N]"
    fbar.ComponentTitle = ""
    fbar.TitleColor = fbar.LabelColor = [0.1, 0.1, 0.1]
    fbar.RangeLabelFormat = "%-#.3g"

    for v in (left, right):
        od = pv.Show(outline, v)
        od.AmbientColor = od.DiffuseColor = [0.2, 0.2, 0.2]
        od.LineWidth = 2.0

    title = a.title or os.path.basename(stem)
    for v, text in ((left, f"{title}: {n_spheres} spheres"),
                    (right, f"contact network: {n_contacts} contacts (tube radius and colour: "
                            "normal force)")):
        t = pv.Text(Text=text)
        tdp = pv.Show(t, v)
        tdp.Color = [0.1, 0.1, 0.1]
        tdp.FontSize = 14
        tdp.WindowLocation = "Upper Center"

    # The same oblique camera in both panels.
    for v in (left, right):
        v.CameraPosition = [1.0, -1.6, 0.9]
        v.CameraFocalPoint = [0.0, 0.0, 0.0]
        v.CameraViewUp = [0.0, 0.0, 1.0]
        v.ResetCamera()
        v.CameraParallelProjection = 0
    pv.AddCameraLink(left, right, "rve_camera")
    left.ResetCamera()
    pv.Render(left)
    pv.Render(right)
    pv.SaveScreenshot(a.png, layout, ImageResolution=[width, height],
                      OverrideColorPalette="WhiteBackground")
    if a.colors > 0:
        try:
            from PIL import Image
        except ImportError:
            print("render_rve: Pillow is not installed: the PNG keeps its true colours")
        else:
            Image.open(a.png).convert("RGB").quantize(colors=a.colors).save(a.png, optimize=True)
    print(f"render_rve: {a.png}: {n_spheres} spheres, {n_contacts} contacts, normal force "
          f"{fn_range[0]:.3g} .. {fn_range[1]:.3g} N")
    return 0


if __name__ == "__main__":
    sys.exit(main())
