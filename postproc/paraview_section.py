"""A ParaView (pvpython) example: the section of a udar field file through a plane, coloured
by an element field, saved as an image. Needs Debian's paraview and python3-paraview; with
no display, run it under a virtual X server:

    xvfb-run -a pvpython --force-offscreen-rendering postproc/paraview_section.py \\
        input/taylor_ofhc/out/taylor_ofhc.xmf -o section.png --field pressure

Give the .xmf with a directory (``./case.xmf``, not ``case.xmf``): ParaView's Xdmf3 reader
resolves the .h5 it names against the .xmf's directory and mis-resolves a bare file name.
The last output step is drawn (``--time T_US`` picks another), the plane is y = 0 through the
origin (``--normal``, ``--origin``), the map a diverging one centred on zero for fields of
both signs. What it shows is written in the picture's corner: file, step time, field, unit.
"""
import argparse
import os
import sys

UNITS = {"pressure": "Pa", "von_mises": "Pa", "plastic_strain": "-", "temperature": "K",
         "density": "kg/m3", "time_step": "s", "damage": "-"}


def main(argv=None):
    p = argparse.ArgumentParser(prog="paraview_section.py", description=__doc__.split("\n")[0])
    p.add_argument("xmf", help="udar XDMF index (<case>.xmf), with its directory")
    p.add_argument("-o", "--output", default="section.png", help="image file (default section.png)")
    p.add_argument("--field", default="pressure", help="element field to colour by (default pressure)")
    p.add_argument("--time", type=float, default=None, metavar="T_US", help="time in us (default: last step)")
    p.add_argument("--normal", type=float, nargs=3, default=(0.0, 1.0, 0.0), help="plane normal (default 0 1 0)")
    p.add_argument("--origin", type=float, nargs=3, default=(0.0, 0.0, 0.0), help="a point on the plane, m")
    args = p.parse_args(argv)
    xmf = args.xmf if os.path.dirname(args.xmf) else os.path.join(".", args.xmf)
    if not os.path.isfile(xmf):
        print("paraview_section.py: %s: no such file" % xmf, file=sys.stderr)
        return 1

    from paraview import simple as pv
    reader = pv.Xdmf3ReaderS(FileName=[xmf])
    times = list(reader.TimestepValues) if reader.TimestepValues else [0.0]
    t = times[-1] if args.time is None else min(times, key=lambda v: abs(v - args.time * 1e-6))
    cut = pv.Slice(Input=reader)
    cut.SliceType = "Plane"
    cut.SliceType.Origin = list(args.origin)
    cut.SliceType.Normal = list(args.normal)
    view = pv.CreateRenderView()
    view.ViewSize = [1000, 1000]
    view.ViewTime = t
    view.OrientationAxesVisibility = 1
    shown = pv.Show(cut, view)
    pv.ColorBy(shown, ("CELLS", args.field))
    lut = pv.GetColorTransferFunction(args.field)
    cut.UpdatePipeline(t)
    if cut.GetDataInformation().GetNumberOfCells() == 0:
        # the plane lies on the body's face (the symmetry plane of a half or quarter model):
        # cut a hair inside it
        b = reader.GetDataInformation().GetBounds()
        size = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
        cut.SliceType.Origin = [o + 1e-6 * size * n for o, n in zip(args.origin, args.normal)]
        cut.UpdatePipeline(t)
    data = cut.CellData[args.field]
    if data is None:
        print("paraview_section.py: %s: no cell field %r at t = %g s (fields: %s)" % (
            xmf, args.field, t, ", ".join(cut.CellData.keys())), file=sys.stderr)
        return 1
    lo, hi = data.GetRange()
    if lo < 0.0 < hi:
        # both signs: a diverging map with white at zero
        lut.ApplyPreset("Cool to Warm", True)
        m = max(-lo, hi)
        lut.RescaleTransferFunction(-m, m)
    else:
        lut.ApplyPreset("Viridis (matplotlib)", True)
        lut.RescaleTransferFunction(lo, hi)
    bar = pv.GetScalarBar(lut, view)
    bar.Title = "%s (%s)" % (args.field, UNITS.get(args.field, ""))
    bar.ComponentTitle = ""
    shown.SetScalarBarVisibility(view, True)
    text = pv.Text(Text="%s\nt = %.3f us, plane normal %s through %s m" % (
        os.path.basename(xmf), t * 1e6, tuple(args.normal), tuple(args.origin)))
    pv.Show(text, view)
    # look along the plane's normal
    view.CameraPosition = [o - n for o, n in zip(args.origin, args.normal)]
    view.CameraFocalPoint = list(args.origin)
    view.CameraViewUp = [0.0, 0.0, 1.0] if abs(args.normal[2]) < 0.9 else [0.0, 1.0, 0.0]
    view.ResetCamera()
    pv.SaveScreenshot(args.output, view, ImageResolution=[1000, 1000])
    print("wrote %s (t = %.3f us, %s %.4g .. %.4g %s)" % (args.output, t * 1e6, args.field, lo, hi,
                                                        UNITS.get(args.field, "")))
    return 0


if __name__ == "__main__":
    rc = main()
    sys.stdout.flush()
    # leave without ParaView's teardown, which under xvfb can abort on a GLX context
    # after the image is written (measured with pvpython 5.11 here)
    os._exit(rc)
