#!/usr/bin/python3
"""Renders grain-scale views written by `mpmxdem inspect CKPT --rve ID --vtk DIR` to a PNG with
ParaView: one row per view (RVE), one column per panel; the periodic cell outlined in each.

  xvfb-run -a tools/mpmxdem-tools render_rve VTM [VTM ...] OUT.png
      [--panels grains,normal,shear] [--color radius|velocity|spin|contacts]
      [--size 1600x800] [--title TEXT] [--colors 256]

Panels: `grains` the spheres coloured by a sphere array (--color; vectors: their magnitude);
`normal` the contact network as tubes whose radius and colour follow the normal force; `shear`
the same with the shear force magnitude. Colour scales are shared by the rows. Needs
python3-paraview (Debian 12: paraview 5.11) and, without a display, xvfb-run. The figures
docs/figures/rve_grains.png (one RVE, grains + normal) and docs/figures/rve_neighbours_forces.png
(two neighbour RVEs, normal + shear) were made with it (docs/design/dem.md, "Grain-scale views").
"""

import argparse
import os
import sys

BAR_TITLES = {"radius": "radius [m]", "velocity": "|velocity| [m/s]", "spin": "|spin| [rad/s]",
              "contacts": "contacts per sphere", "normal_force": "normal force [N]",
              "shear_force_magnitude": "shear force [N]"}


def files_of(vtm):
    stem = vtm[:-len(".vtm")] if vtm.endswith(".vtm") else vtm
    files = {b: stem + suffix for b, suffix in
             (("spheres", "_spheres.vtp"), ("contacts", "_contacts.vtp"), ("cell", "_cell.vtu"))}
    for f in files.values():
        if not os.path.exists(f):
            sys.exit(f"render_rve: {f} is missing (write the view with mpmxdem inspect --vtk)")
    return os.path.basename(stem), files


def grid(layout, rows, cols):
    """Splits the layout into rows x cols equal cells; returns their locations [row][col]."""
    def split(loc, n, vertical):
        if n == 1:
            return [loc]
        (layout.SplitVertical if vertical else layout.SplitHorizontal)(loc, 1.0 / n)
        return [2 * loc + 1] + split(2 * loc + 2, n - 1, vertical)
    return [split(r, cols, False) for r in split(0, rows, True)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("vtm", nargs="+", help="rve_<id>_step_<step>.vtm written by inspect --vtk")
    ap.add_argument("png")
    ap.add_argument("--panels", default="grains,normal",
                    help="columns, among grains, normal, shear (default grains,normal)")
    ap.add_argument("--color", default="radius", choices=["radius", "velocity", "spin", "contacts"],
                    help="sphere array of the grains panel (vectors: their magnitude)")
    ap.add_argument("--size", default="1600x800", help="image size in pixels, WxH")
    ap.add_argument("--title", default=None,
                    help="text above the first panel of the first row (default: the file name)")
    ap.add_argument("--colors", type=int, default=0,
                    help="reduce the PNG to this many colours with Pillow if installed (256: "
                         "about 4 times smaller; 0: keep true colour)")
    a = ap.parse_args()
    panels = a.panels.split(",")
    for p in panels:
        if p not in ("grains", "normal", "shear"):
            sys.exit(f"render_rve: --panels: unknown panel '{p}' (grains, normal, shear)")
    views_in = [files_of(v) for v in a.vtm]
    width, height = (int(v) for v in a.size.split("x"))

    from paraview import simple as pv
    from paraview import servermanager as sm

    rows = []
    force_max = {"normal_force": 0.0, "shear_force_magnitude": 0.0}
    r_min = float("inf")
    for name, files in views_in:
        row = {"name": name,
               "spheres": pv.XMLPolyDataReader(FileName=[files["spheres"]]),
               "contacts": pv.XMLPolyDataReader(FileName=[files["contacts"]]),
               "cell": pv.XMLUnstructuredGridReader(FileName=[files["cell"]])}
        sd = sm.Fetch(row["spheres"])
        cd = sm.Fetch(row["contacts"])
        row["n_spheres"] = sd.GetNumberOfPoints()
        row["n_contacts"] = cd.GetNumberOfCells()
        r_min = min(r_min, sd.GetPointData().GetArray("radius").GetRange()[0])
        for f in force_max:
            if row["n_contacts"]:
                force_max[f] = max(force_max[f], cd.GetCellData().GetArray(f).GetRange()[1])
        rows.append(row)

    layout = pv.CreateLayout("rve")
    cells = grid(layout, len(rows), len(panels))
    layout.SetSize(width, height)
    views = []

    def scalar_bar(array, view, preset, invert, rng):
        lut = pv.GetColorTransferFunction(array)
        lut.ApplyPreset(preset, True)
        if invert:
            lut.InvertTransferFunction()
        if rng is not None:
            lut.RescaleTransferFunction(*rng)
        bar = pv.GetScalarBar(lut, view)
        bar.Title = BAR_TITLES[array]
        bar.ComponentTitle = ""
        bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
        bar.RangeLabelFormat = "%-#.3g"
        bar.TitleFontSize = 12
        bar.LabelFontSize = 11
        bar.ScalarBarLength = 0.3

    for i, row in enumerate(rows):
        for j, panel in enumerate(panels):
            v = pv.CreateView("RenderView")
            layout.AssignView(cells[i][j], v)
            v.OrientationAxesVisibility = 1
            v.Background = [1.0, 1.0, 1.0]
            try:
                v.UseColorPaletteForBackground = 0
            except AttributeError:
                pass
            if panel == "grains":
                # One sphere glyph per point at its true radius (the glyph source has radius 0.5).
                glyph = pv.Glyph(Input=row["spheres"], GlyphType="Sphere")
                glyph.ScaleArray = ["POINTS", "radius"]
                glyph.ScaleFactor = 2.0
                glyph.GlyphMode = "All Points"
                glyph.GlyphType.ThetaResolution = 16
                glyph.GlyphType.PhiResolution = 12
                d = pv.Show(glyph, v)
                vector = a.color in ("velocity", "spin")
                pv.ColorBy(d, ("POINTS", a.color, "Magnitude") if vector else ("POINTS", a.color))
                d.SetScalarBarVisibility(v, True)
                scalar_bar(a.color, v, "Viridis (matplotlib)", False, None)
                text = f"{row['n_spheres']} spheres"
            else:
                # Tubes of radius 0.03 .. 0.53 of the smallest sphere radius, growing with the force.
                f = "normal_force" if panel == "normal" else "shear_force_magnitude"
                c2p = pv.CellDatatoPointData(Input=row["contacts"])
                calc = pv.Calculator(Input=c2p)
                calc.ResultArrayName = "tube_radius"
                calc.Function = f"{r_min} * (0.03 + 0.50 * {f} / {max(force_max[f], 1e-300)})"
                tube = pv.Tube(Input=calc)
                tube.Scalars = ["POINTS", "tube_radius"]
                tube.VaryRadius = "By Absolute Scalar"
                tube.NumberofSides = 10
                tube.Capping = 1
                d = pv.Show(tube, v)
                pv.ColorBy(d, ("POINTS", f))
                d.SetScalarBarVisibility(v, True)
                scalar_bar(f, v, "Inferno (matplotlib)", True, (0.0, force_max[f]))
                text = f"{row['n_contacts']} contacts, {panel} force"
            od = pv.Show(pv.Outline(Input=row["cell"]), v)
            od.AmbientColor = od.DiffuseColor = [0.2, 0.2, 0.2]
            od.LineWidth = 2.0
            head = (a.title or row["name"]) if (i, j) == (0, 0) else row["name"]
            t = pv.Show(pv.Text(Text=f"{head}: {text}"), v)
            t.Color = [0.1, 0.1, 0.1]
            t.FontSize = 11
            t.WindowLocation = "Upper Center"
            # The same oblique camera in every panel.
            v.CameraPosition = [1.0, -1.6, 0.9]
            v.CameraFocalPoint = [0.0, 0.0, 0.0]
            v.CameraViewUp = [0.0, 0.0, 1.0]
            v.ResetCamera()
            views.append(v)
    for k, v in enumerate(views[1:]):
        pv.AddCameraLink(views[0], v, f"rve_camera_{k}")
    views[0].ResetCamera()
    for v in views:
        pv.Render(v)
    pv.SaveScreenshot(a.png, layout, ImageResolution=[width, height],
                      OverrideColorPalette="WhiteBackground")
    if a.colors > 0:
        try:
            from PIL import Image
        except ImportError:
            print("render_rve: Pillow is not installed: the PNG keeps its true colours")
        else:
            Image.open(a.png).convert("RGB").quantize(colors=a.colors).save(a.png, optimize=True)
    for row in rows:
        print(f"render_rve: {a.png}: {row['name']}: {row['n_spheres']} spheres, "
              f"{row['n_contacts']} contacts")
    print(f"render_rve: largest normal force {force_max['normal_force']:.3g} N, shear force "
          f"{force_max['shear_force_magnitude']:.3g} N")
    return 0


if __name__ == "__main__":
    sys.exit(main())
