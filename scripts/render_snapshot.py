"""Renders one instant of a cgdem run to PNG with ParaView: the parcels coloured by speed
and a slice of the air (pressure or porosity) through the domain.

    xvfb-run -a pvpython scripts/render_snapshot.py RUN_DIR [--time T] [--output PNG]
        [--field p|eps|alpha] [--slice-y Y] [--size 1400x800] [--reader xdmf|xdmf3s|xdmf3t]

RUN_DIR is a run folder of `cgdem run` (particles.xdmf, and air.xdmf when the case has
air). --time picks the snapshot nearest T (seconds; default: the last one); --slice-y the
plane y = Y of the air slice (metres; default: the middle of the grid), seen from -y with
z up, the parcels in front of it. Debian: apt-get install paraview python3-paraview xvfb
(pvpython needs a display: xvfb-run gives it one).
"""
import argparse
import os
import sys

from paraview import simple as pv

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ap.add_argument("run_dir")
ap.add_argument("--time", type=float, default=None, help="simulated time [s] (nearest snapshot; default: last)")
ap.add_argument("--output", default=None, help="PNG file (default: RUN_DIR/snapshot_<t>.png)")
ap.add_argument("--field", default="p", choices=["p", "eps", "alpha"], help="air field on the slice")
ap.add_argument("--slice-y", type=float, default=None, help="y of the slice plane [m] (default: grid middle)")
ap.add_argument("--size", default="1400x800", help="image size WxH in pixels")
ap.add_argument("--full", action="store_true", help="frame the whole grid (default: the powder and the die)")
ap.add_argument("--reader", default="xdmf3t", choices=["xdmf", "xdmf3s", "xdmf3t"],
                help="ParaView reader: XDMFReader, Xdmf3ReaderS or Xdmf3ReaderT (default)")
args = ap.parse_args()

particles_xdmf = os.path.join(args.run_dir, "particles.xdmf")
air_xdmf = os.path.join(args.run_dir, "air.xdmf")
if not os.path.exists(particles_xdmf):
    sys.exit(f"render_snapshot: {particles_xdmf} does not exist (not a cgdem run folder?)")
readers = {"xdmf": pv.XDMFReader, "xdmf3s": pv.Xdmf3ReaderS, "xdmf3t": pv.Xdmf3ReaderT}
Reader = readers[args.reader]


def open_xdmf(path):
    # XDMFReader names its file list FileNames, the Xdmf3 readers FileName.
    return Reader(FileNames=[path]) if args.reader == "xdmf" else Reader(FileName=[path])


particles = open_xdmf(particles_xdmf)
steps = particles.TimestepValues  # a property: a list, or one number for a single step
try:
    times = [float(v) for v in steps]
except TypeError:
    times = [float(steps)] if steps is not None else [0.0]
times = times or [0.0]
t = times[-1] if args.time is None else min(times, key=lambda x: abs(x - args.time))
scene = pv.GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = t

width, height = (int(v) for v in args.size.lower().split("x"))
view = pv.CreateView("RenderView")
view.ViewSize = [width, height]
view.Background = [1, 1, 1]
try:  # ParaView >= 5.10 uses a palette unless told otherwise
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
view.OrientationAxesVisibility = 1
view.ViewTime = t

# Parcels as spheres of their diameter, coloured by speed |v|.
speed = pv.Calculator(Input=particles, AttributeType="Point Data", ResultArrayName="speed",
                      Function="mag(velocity)")
pd = pv.Show(speed, view)
pd.SetRepresentationType("Point Gaussian")
pd.ScaleByArray = 1
pd.SetScaleArray = ["POINTS", "diameter"]
pd.ScaleTransferFunction.Points = [0.0, 0.0, 0.5, 0.0, 1.0, 1.0, 0.5, 0.0]
pd.GaussianRadius = 0.5
pd.ShaderPreset = "Sphere"
pv.ColorBy(pd, ("POINTS", "speed"))
speed_lut = pv.GetColorTransferFunction("speed")
speed_lut.ApplyPreset("Viridis (matplotlib)", True)
speed.UpdatePipeline(t)
srange = speed.PointData["speed"].GetRange() if speed.PointData.GetArray("speed") else (0.0, 1.0)
speed_lut.RescaleTransferFunction(0.0, max(srange[1], 1e-6))
pd.SetScalarBarVisibility(view, True)
bar = pv.GetScalarBar(speed_lut, view)
bar.Title = "parcel speed [m/s]"
bar.ComponentTitle = ""
bar.WindowLocation = "Any Location"
bar.Position = [0.89, 0.05]
bar.TitleColor = bar.LabelColor = [0, 0, 0]

pbounds = particles.GetDataInformation().GetBounds()
bounds = pbounds
label = f"t = {t:.4f} s, {particles.GetDataInformation().GetNumberOfPoints()} parcels"

if os.path.exists(air_xdmf):
    air = open_xdmf(air_xdmf)
    air.UpdatePipeline(t)
    bounds = air.GetDataInformation().GetBounds()
    y = 0.5 * (bounds[2] + bounds[3]) if args.slice_y is None else args.slice_y
    # Cells mostly inside walls are left out: the walls show as blank, and the colour range
    # is that of the air.
    fluid = pv.Threshold(Input=air)
    fluid.Scalars = ["CELLS", "alpha"]
    try:  # ParaView >= 5.10
        fluid.LowerThreshold, fluid.UpperThreshold = 0.0, 0.5
    except AttributeError:
        fluid.ThresholdRange = [0.0, 0.5]
    cut = pv.Slice(Input=fluid)
    cut.SliceType = "Plane"
    cut.SliceType.Origin = [0.5 * (bounds[0] + bounds[1]), y, 0.5 * (bounds[4] + bounds[5])]
    cut.SliceType.Normal = [0.0, 1.0, 0.0]
    sd = pv.Show(cut, view)
    pv.ColorBy(sd, ("CELLS", args.field))
    lut = pv.GetColorTransferFunction(args.field)
    lut.ApplyPreset("Cool to Warm", True)
    cut.UpdatePipeline(t)
    arr = cut.CellData.GetArray(args.field)
    if arr:
        lo, hi = arr.GetRange()
        lut.RescaleTransferFunction(lo, hi if hi > lo else lo + 1e-12)
    sd.Opacity = 0.85
    sd.SetScalarBarVisibility(view, True)
    abar = pv.GetScalarBar(lut, view)
    abar.Title = {"p": "air pressure [Pa]", "eps": "air volume fraction [1]", "alpha": "wall fraction [1]"}[args.field]
    abar.ComponentTitle = ""
    abar.WindowLocation = "Any Location"
    abar.Position = [0.02, 0.05]
    abar.TitleColor = abar.LabelColor = [0, 0, 0]
    label += f"; air {args.field} on the plane y = {y * 1e3:.2f} mm"

text = pv.Text(Text=label)
td = pv.Show(text, view)
td.Color = [0, 0, 0]
td.FontSize = 14
td.WindowLocation = "Upper Center"

# Seen from -y (the slice plane faces the camera), z up; framed on the powder and what lies
# below it (the die), or with --full on the whole grid.
x0, x1, z0, z1 = bounds[0], bounds[1], bounds[4], bounds[5]
if not args.full and pbounds[1] > pbounds[0]:
    w = pbounds[1] - pbounds[0]
    x0, x1 = max(x0, pbounds[0] - 0.6 * w), min(x1, pbounds[1] + 0.6 * w)
    z1 = min(z1, pbounds[5] + 0.3 * (pbounds[5] - z0))
cx, cy, cz = 0.5 * (x0 + x1), 0.5 * (bounds[2] + bounds[3]), 0.5 * (z0 + z1)
view.CameraPosition = [cx, cy - 10 * max(x1 - x0, z1 - z0), cz]
view.CameraFocalPoint = [cx, cy, cz]
view.CameraViewUp = [0, 0, 1]
view.CameraParallelProjection = 1
view.CameraParallelScale = 0.55 * max(z1 - z0, (x1 - x0) * height / width)

out = args.output or os.path.join(args.run_dir, f"snapshot_{t:.4f}.png")
pv.SaveScreenshot(out, view, ImageResolution=[width, height])
print(f"render_snapshot: {out} (t = {t:.6g} s of {len(times)} snapshots)")
