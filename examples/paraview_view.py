"""Pictures of a sizemesh mesh with ParaView: one PNG per field, rendered off-screen.

    sizemesh model.stp -o mesh.vtu --background bg.vtu
    pvpython examples/paraview_view.py mesh.vtu [--background bg.vtu] [--out DIR] [--size WxH]
                                       [--supersample N] [--view X,Y,Z]

Writes into DIR (default: the current directory), each surface-with-edges with a colour bar:
  <mesh>_target_size.png   the size asked for at each node (log scale)
  <mesh>_min_angle.png     each triangle's smallest angle (degrees)
  <bg>_h_smoothed.png      the size map on the background mesh (log scale)
  <mesh>_limited_by.png    what set the size at each node (curvature, proximity, h_max, a source, ...)
  <bg>_limited_by.png      what set each background vertex's size
A field missing from its file is skipped with a note. Debian's ParaView renders through X
only: without a display the script starts a virtual X server, Xvfb (Debian package xvfb), for itself.
SIZEMESH_PARAVIEW_PYTHON, when set, is the folder of ParaView's Python package (put first on the path).
"""
import argparse
import os
import shutil
import sys

# ParaView's Python package from another folder, ahead of everything pvpython puts on the path
# (cmake/setup.sh unpacks Debian's python3-paraview so, since it cannot be installed beside the
# python3-vtk9 that libvtk9-dev needs; see docs/paraview.md).
if os.environ.get("SIZEMESH_PARAVIEW_PYTHON"):
    sys.path.insert(0, os.environ["SIZEMESH_PARAVIEW_PYTHON"])

# Codes of sizemesh's Limit enum (sizing/size_map.h) as written to limited_by (mesh and background).
LIMITS = ["h_max", "curvature", "face proximity", "curve length", "gap (fluid)", "thickness (solid)",
          "user size", "h_min", "far-field size", "size source", "wing feature"]
LIMIT_COLOURS = [(0.65, 0.65, 0.65), (0.89, 0.10, 0.11), (0.22, 0.49, 0.72), (0.30, 0.69, 0.29),
                 (0.60, 0.31, 0.64), (1.00, 0.50, 0.00), (0.97, 0.51, 0.75), (0.65, 0.34, 0.16),
                 (0.10, 0.75, 0.80), (1.00, 0.85, 0.10), (0.05, 0.05, 0.05)]

# (file, array, colour-bar title, scale): file "mesh" or "background"; scale "log", "linear" or "categories".
FIELDS = [("mesh", "target_size", "target size", "log"),
          ("mesh", "min_angle", "min angle (deg)", "linear"),
          ("mesh", "limited_by", "size limited by", "categories"),
          ("background", "h_smoothed", "size map (background)", "log"),
          ("background", "limited_by", "size limited by", "categories")]

BACKGROUND_COLOUR = [1.0, 1.0, 1.0]
TEXT_COLOUR = [0.1, 0.1, 0.1]


def parse_args():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("mesh", help="surface mesh written by sizemesh -o MESH.vtu")
    p.add_argument("--background", help="background mesh written by sizemesh --background BG.vtu")
    p.add_argument("--out", default=".", help="directory for the PNG files (default: .)")
    p.add_argument("--size", default="1000x600", help="picture size in pixels, WxH (default 1000x600)")
    p.add_argument("--supersample", type=int, default=2, choices=range(1, 5), metavar="N",
                   help="render N times larger and scale down (default 2): edges of a fine mesh "
                        "then darken its colours instead of hiding them")
    p.add_argument("--view", default=None,
                   help="camera direction from the model's centre, x,y,z (default: isometric, "
                        "from the front, the side and above; 'above' is the model's thinnest axis)")
    a = p.parse_args()
    try:
        a.size = [int(n) for n in a.size.lower().split("x")]
        assert len(a.size) == 2 and min(a.size) >= 16
    except (ValueError, AssertionError):
        p.error("--size: expected WxH in pixels, e.g. 1000x600")
    if a.view is not None:
        try:
            a.view = [float(c) for c in a.view.split(",")]
            assert len(a.view) == 3 and any(a.view)
        except (ValueError, AssertionError):
            p.error("--view: expected a direction x,y,z, e.g. -1,-1,1")
    for f in (a.mesh, a.background):
        if f and not os.path.isfile(f):
            p.error("no such file: %s" % f)
    return a


def start_xvfb():
    """Start a virtual X server (Xvfb, with Mesa's software OpenGL) and point DISPLAY at it. The display
    number is drawn at random from a wide range (a taken one is tried again): -displayfd's own choice of
    the lowest free number, like xvfb-run -a, races with other servers starting at the same time.
    The server gets SIGTERM when this process has ended (PR_SET_PDEATHSIG), after VTK's last X call:
    ending it earlier, at exit, makes Xlib abort the process."""
    import ctypes
    import random
    import select
    import signal
    import subprocess

    xvfb = shutil.which("Xvfb")
    if not xvfb:
        sys.exit("paraview_view.py: no X display and no Xvfb: this ParaView renders through X "
                 "(GLX); install Debian's xvfb (apt-get install xvfb) or set DISPLAY")
    libc = ctypes.CDLL(None, use_errno=True)
    for _ in range(20):
        display = random.randrange(100, 30000)
        read_end, write_end = os.pipe()
        # -noreset: a server resetting after its first client leaves refuses the next (VTK connects twice).
        command = [xvfb, ":%d" % display, "-displayfd", str(write_end), "-screen", "0", "1280x1024x24",
                   "-nolisten", "tcp", "-noreset"]
        server = subprocess.Popen(command, pass_fds=(write_end,), stdin=subprocess.DEVNULL,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                  preexec_fn=lambda: libc.prctl(1, signal.SIGTERM))  # 1: PR_SET_PDEATHSIG
        os.close(write_end)
        ready = b""  # the server writes its number once it accepts connections, or exits (number taken)
        while not ready.endswith(b"\n") and select.select([read_end], [], [], 30)[0]:
            chunk = os.read(read_end, 16)
            if not chunk:
                break
            ready += chunk
        os.close(read_end)
        if ready.strip() == str(display).encode() and server.poll() is None:
            os.environ["DISPLAY"] = ":%d" % display
            return
        server.kill()
        server.wait()
    sys.exit("paraview_view.py: Xvfb did not start")


def render_off_screen():
    """Render without a window. Debian's ParaView has an X (GLX) render window only, no EGL or OSMesa:
    without a display it renders on a virtual X server; on a real display the script restarts as
    `pvpython --force-offscreen-rendering` (unless so started) so that no window opens."""
    from paraview.modules.vtkRemotingCore import vtkRemotingCoreConfiguration
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (registers the platform's render window)
    from vtkmodules.vtkRenderingCore import vtkRenderWindow

    if vtkRenderWindow().GetClassName() != "vtkXOpenGLRenderWindow":
        return  # EGL or OSMesa build: off-screen needs no X at all
    if not os.environ.get("DISPLAY"):
        start_xvfb()  # nothing shows on a virtual display
    elif not vtkRemotingCoreConfiguration.GetInstance().GetForceOffscreenRendering():
        exe = shutil.which(getattr(sys, "orig_argv", ["pvpython"])[0]) or shutil.which("pvpython")
        command = [exe, "--force-offscreen-rendering", os.path.abspath(__file__)] + sys.argv[1:]
        sys.stdout.flush()
        os.execv(command[0], command)


def find_array(reader, name):
    """('POINTS' or 'CELLS', range) of the array, or None."""
    for association, arrays in (("POINTS", reader.PointData), ("CELLS", reader.CellData)):
        if name in arrays.keys():
            return association, arrays[name].GetRange()
    return None


def values_present(reader, association, name):
    from paraview import servermanager
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy as np

    data = servermanager.Fetch(reader)
    arrays = data.GetPointData() if association == "POINTS" else data.GetCellData()
    return sorted(int(v) for v in np.unique(vtk_to_numpy(arrays.GetArray(name))))


def colour(reader, display, view, name, title, scale):
    import paraview.simple as pv

    association, (lo, hi) = find_array(reader, name)
    pv.ColorBy(display, (association, name))
    lut = pv.GetColorTransferFunction(name)
    lut.AutomaticRescaleRangeMode = "Never"
    if scale == "categories":
        codes = values_present(reader, association, name)
        lut.InterpretValuesAsCategories = 1
        lut.AnnotationsInitialized = 1
        lut.Annotations = sum(([str(c), LIMITS[c] if 0 <= c < len(LIMITS) else str(c)] for c in codes), [])
        lut.IndexedColors = sum((list(LIMIT_COLOURS[c % len(LIMIT_COLOURS)]) for c in codes), [])
        lut.IndexedOpacities = [1.0] * len(codes)
    else:
        lut.ApplyPreset("Viridis (matplotlib)" if scale == "log" else "Plasma (matplotlib)", True)
        if hi <= lo:
            hi = lo * 1.01 if lo > 0 else lo + 1
        lut.RescaleTransferFunction(lo, hi)
        if scale == "log" and lo > 0:
            lut.MapControlPointsToLogSpace()
            lut.UseLogScale = 1
    bar = pv.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = TEXT_COLOUR
    bar.TitleFontSize = 18
    bar.LabelFontSize = 15
    bar.WindowLocation = "Any Location"
    bar.Orientation = "Vertical"
    bar.Position = [0.88, 0.12]
    bar.ScalarBarLength = 0.7
    if scale == "categories":
        bar.TextPosition = "Ticks left/bottom, annotations right/top"
        bar.Position = [0.86, 0.15]
    else:
        bar.RangeLabelFormat = "%-#6.3g"
        bar.AddRangeLabels = 1
    bar.Visibility = 1
    return lut


def model_points(reader, limit=200000):
    """The mesh's node coordinates (numpy, at most `limit` of them) for framing the camera."""
    from paraview import servermanager
    from vtkmodules.util.numpy_support import vtk_to_numpy

    points = vtk_to_numpy(servermanager.Fetch(reader).GetPoints().GetData())
    return points[:: max(1, len(points) // limit)]


def place_camera(view, points, direction, size):
    """Perspective view of every point from `direction` (default isometric: from the front, the side
    and above, 'above' being the thinnest axis of the box: z for an aircraft), as close as the points
    allow with the right part of the picture left to the colour bar."""
    import numpy as np

    lo, hi = points.min(axis=0), points.max(axis=0)
    up_axis = int(np.argmin(hi - lo))
    if direction is None:
        direction = [-1.0, -1.0, -1.0]
        direction[up_axis] = 0.9
    d = np.asarray(direction, float) / np.linalg.norm(direction)  # from the model towards the camera
    u = np.eye(3)[up_axis] - np.dot(np.eye(3)[up_axis], d) * d
    if np.linalg.norm(u) < 1e-6:  # looking along the up axis
        u = np.eye(3)[(up_axis + 1) % 3] - np.dot(np.eye(3)[(up_axis + 1) % 3], d) * d
    u /= np.linalg.norm(u)
    r = np.cross(-d, u)  # screen right
    centre = (lo + hi) / 2
    q = points - centre
    x, y, z = q @ r, q @ u, q @ d
    t = np.tan(np.radians(view.CameraViewAngle) / 2)
    # Screen coordinates in [-1, 1]: the model in [-0.96, 0.66] across (the bar on the right), [-0.9, 0.9] up.
    # A point is on screen at (x - s) / (k (D - z)) with k = t * aspect across, t up; the least distance D
    # that fits every point, and the shift s of the focal point, for each direction in closed form.
    fits = []
    for c, k, (a, b) in ((x, t * size[0] / size[1], (-0.96, 0.66)), (y, t, (-0.9, 0.9))):
        high, low = np.max(c + b * k * z), np.min(c + a * k * z)
        fits.append((high, low, k, a, b, (high - low) / ((b - a) * k)))
    distance = max(f[5] for f in fits)
    shift = [(high - b * k * distance + low - a * k * distance) / 2 for high, low, k, a, b, _ in fits]
    focal = centre + shift[0] * r + shift[1] * u
    view.CameraParallelProjection = 0
    view.CameraFocalPoint = list(focal)
    view.CameraPosition = list(focal + distance * d)
    view.CameraViewUp = list(u)
    view.CenterOfRotation = list(centre)


def save_png(view, png, size, supersample):
    """The view as a PNG of `size` pixels, rendered `supersample` times larger (fonts too) and scaled down."""
    import paraview.simple as pv

    if supersample == 1:
        pv.SaveScreenshot(png, view, ImageResolution=size, TransparentBackground=0)
        return
    from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter
    from vtkmodules.vtkImagingCore import vtkImageResize

    large = png + ".large.png"
    pv.SaveScreenshot(large, view, ImageResolution=[n * supersample for n in size], TransparentBackground=0,
                      FontScaling="Scale fonts proportionally")
    reader = vtkPNGReader()
    reader.SetFileName(large)
    resize = vtkImageResize()  # windowed-sinc interpolation, antialiased
    resize.SetInputConnection(reader.GetOutputPort())
    resize.SetOutputDimensions(size[0], size[1], 1)
    writer = vtkPNGWriter()
    writer.SetCompressionLevel(9)
    writer.SetFileName(png)
    writer.SetInputConnection(resize.GetOutputPort())
    writer.Write()
    os.remove(large)


def main():
    args = parse_args()
    render_off_screen()
    import paraview.simple as pv

    os.makedirs(args.out, exist_ok=True)
    view = pv.CreateView("RenderView")
    view.ViewSize = args.size
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = BACKGROUND_COLOUR
    view.EnableRenderOnInteraction = 0

    readers = {}
    for which, path in (("mesh", args.mesh), ("background", args.background)):
        if path:
            readers[which] = (path, pv.XMLUnstructuredGridReader(FileName=[os.path.abspath(path)]))
            readers[which][1].UpdatePipeline()
    if not readers["mesh"][1].GetDataInformation().GetNumberOfPoints():
        sys.exit("paraview_view.py: no points in %s" % args.mesh)
    points = model_points(readers["mesh"][1])

    written = 0
    for which, name, title, scale in FIELDS:
        if which not in readers:
            print("skipped %s: no --background given" % name)
            continue
        path, reader = readers[which]
        if not find_array(reader, name):
            print("skipped %s: no such point or cell array in %s" % (name, path))
            continue
        source = reader
        if scale == "categories" and find_array(reader, name)[0] == "POINTS":
            # One category per triangle, the most common of its corners': interpolating codes
            # between corners would blend colours that mean nothing. (The vote takes integer arrays only.)
            codes = pv.Calculator(Input=reader, Function=name, ResultArrayName=name, ResultArrayType="Int")
            source = pv.PointDatatoCellData(Input=codes, CategoricalData=1, PassPointData=0)
            source.UpdatePipeline()
        display = pv.Show(source, view)
        display.SetRepresentationType("Surface With Edges")
        display.EdgeColor = [0.15, 0.15, 0.15]
        display.Specular = 0.15
        lut = colour(source, display, view, name, title, scale)
        place_camera(view, points, args.view, args.size)
        stem = os.path.splitext(os.path.basename(path))[0]
        png = os.path.join(args.out, "%s_%s.png" % (stem, name))
        save_png(view, png, args.size, args.supersample)
        pv.GetScalarBar(lut, view).Visibility = 0
        pv.Hide(source, view)
        print("wrote %s (%s, %dx%d)" % (png, name, args.size[0], args.size[1]))
        written += 1
    if not written:
        sys.exit("paraview_view.py: no field to show in %s" % ", ".join(p for p, _ in readers.values()))


if __name__ == "__main__":
    main()
