#!/usr/bin/env python3
"""Draws a ritr run the way the r-ITR paper shows it: the deformed mesh coloured by a strain or
stress measure, with its edges and the obstacles, beside the (adapted) reference mesh.

    scripts/render.py RUN_DIR [--frames 0 -1] [--out DIR] [--field strain] [--no-animation]
                      [--camera X Y Z --up X Y Z --zoom F]  (3D: the view)

writes OUT/figure-NNNNN.png for the chosen frames (indices into solution.pvd; negative ones
count from the end) and, unless --no-animation, OUT/animation/frame-NNNNN.png for every frame
and OUT/animation.gif. OUT defaults to RUN_DIR/pictures. It runs in ParaView's pvbatch; started
with another Python it hands itself over to scripts/pvbatch.sh.
"""
import argparse
import os
import sys

try:
    import numpy
    from paraview import servermanager
    from paraview import simple as pv
    from vtkmodules.util.numpy_support import vtk_to_numpy
except ImportError:
    wrapper = os.path.join(os.path.dirname(os.path.abspath(__file__)), "pvbatch.sh")
    os.execv(wrapper, [wrapper, os.path.abspath(__file__)] + sys.argv[1:])

FIELDS = {"strain": "CELLS", "von_mises_stress": "CELLS", "element_quality": "CELLS",
          "contact_pressure": "POINTS"}


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run_dir", help="a ritr output directory (with solution.pvd)")
    parser.add_argument("--frames", type=int, nargs="+", default=[-1],
                        help="frames of the figure (default: the last)")
    parser.add_argument("--out", help="where the pictures go (default: RUN_DIR/pictures)")
    parser.add_argument("--field", default="strain", choices=sorted(FIELDS),
                        help="colour of the deformed mesh (default: strain)")
    parser.add_argument("--size", type=int, nargs=2, default=[1600, 800], metavar=("W", "H"))
    parser.add_argument("--no-animation", action="store_true", help="draw only the figure")
    parser.add_argument("--camera", type=float, nargs=3, default=[1, -1.5, 1], metavar=("X", "Y", "Z"),
                        help="3D: direction from the scene's centre to the camera (default: 1 -1.5 1)")
    parser.add_argument("--up", type=float, nargs=3, default=[0, 0, 1], metavar=("X", "Y", "Z"),
                        help="3D: the direction drawn upwards (default: 0 0 1)")
    parser.add_argument("--zoom", type=float, default=1.0,
                        help="3D: magnification after framing the whole scene (default: 1)")
    return parser.parse_args()


def time_steps(reader):
    times = reader.TimestepValues  # a number, not a list, when the run has one frame
    return list(times) if hasattr(times, "__len__") else [times]


def bounds_at(source, time):
    source.UpdatePipeline(time)
    return source.GetDataInformation().GetBounds()


EMPTY_BOUNDS = [float("inf"), -float("inf")] * 3


def union(a, b):
    return [min(a[i], b[i]) if i % 2 == 0 else max(a[i], b[i]) for i in range(6)]


def colour_range(reader, times, field):
    """From the smallest value to the largest 99th percentile over all frames: one scale for the
    whole animation, not set by the few elements at a contact tip."""
    low, high = float("inf"), -float("inf")
    for t in times:
        reader.UpdatePipeline(t)
        grid = servermanager.Fetch(reader)
        data = grid.GetCellData() if FIELDS[field] == "CELLS" else grid.GetPointData()
        values = vtk_to_numpy(data.GetArray(field))
        low, high = min(low, values.min()), max(high, numpy.percentile(values, 99))
    return low, max(high, low + 1e-12)


class Scene:
    """The pipeline: deformed mesh and obstacles on the left, reference mesh on the right."""

    def __init__(self, run_dir, field, size, camera, up, zoom):
        self.run_dir = run_dir
        self.camera, self.up, self.zoom = camera, up, zoom
        self.solution = pv.PVDReader(FileName=os.path.join(run_dir, "solution.pvd"))
        self.times = time_steps(self.solution)
        self.view = pv.CreateRenderView()
        self.view.ViewSize = size
        self.view.Background = [1, 1, 1]
        self.view.OrientationAxesVisibility = 0
        try:  # ParaView 5.10+: a single background colour needs this switch
            self.view.UseColorPaletteForBackground = 0
        except AttributeError:
            pass
        self.show_deformed(field)
        left = union(bounds_at(self.solution, self.times[0]), self.show_obstacles())
        everything = union(left, self.show_reference_beside(left))
        everything[0] -= 0.15 * (everything[1] - everything[0])  # room for the colour bar
        self.show_labels()
        pv.Render(self.view)  # the first render resets the camera: frame it afterwards
        self.frame_camera(everything)

    def show_mesh(self, source, edge_colour):
        shown = pv.Show(source, self.view)
        shown.SetRepresentationType("Surface With Edges")
        shown.EdgeColor = edge_colour
        return shown

    def show_deformed(self, field):
        deformed = self.show_mesh(self.solution, [0.25, 0.25, 0.25])
        pv.ColorBy(deformed, (FIELDS[field], field))
        colours = pv.GetColorTransferFunction(field)
        colours.ApplyPreset("Viridis (matplotlib)", True)
        colours.RescaleTransferFunction(*colour_range(self.solution, self.times, field))
        colours.AutomaticRescaleRangeMode = "Never"
        bar = pv.GetScalarBar(colours, self.view)
        bar.Title = field.replace("_", " ")
        bar.ComponentTitle = ""
        bar.TitleColor = bar.LabelColor = [0, 0, 0]
        bar.WindowLocation = "Any Location"
        bar.Position = [0.02, 0.1]
        deformed.SetScalarBarVisibility(self.view, True)

    def show_obstacles(self):
        """Shows obstacles.pvd, if the run has obstacles; returns their bounds at the start."""
        path = os.path.join(self.run_dir, "obstacles.pvd")
        if not os.path.exists(path):
            return EMPTY_BOUNDS
        reader = pv.PVDReader(FileName=path)
        shown = pv.Show(reader, self.view)
        shown.SetRepresentationType("Surface")
        shown.ColorArrayName = ["POINTS", ""]
        shown.AmbientColor = shown.DiffuseColor = [0.35, 0.35, 0.35]
        shown.LineWidth = 2.0
        bounds = bounds_at(reader, self.times[0])
        if bounds[5] > bounds[4]:
            shown.Opacity = 0.3  # 3D: the bodies in a gap or behind a block stay visible
        return bounds

    def show_reference_beside(self, left):
        """Shows the reference mesh to the right of the bounds `left`; returns its bounds."""
        reference = pv.PVDReader(FileName=os.path.join(self.run_dir, "reference.pvd"))
        start = bounds_at(reference, self.times[0])
        shift = left[1] - start[0] + 0.05 * (left[1] - left[0])
        moved = pv.Transform(Input=reference)
        moved.Transform.Translate = [shift, 0, 0]
        shown = self.show_mesh(moved, [0.3, 0.3, 0.3])
        shown.ColorArrayName = ["POINTS", ""]
        shown.AmbientColor = shown.DiffuseColor = [0.93, 0.93, 0.93]
        return [b + (shift if i < 2 else 0) for i, b in enumerate(start)]

    def show_labels(self):
        self.clock = pv.Text()
        shown = pv.Show(self.clock, self.view)
        shown.Color = [0, 0, 0]
        shown.WindowLocation = "Upper Left Corner"
        caption = pv.Show(pv.Text(Text="left: deformed mesh and obstacles   right: reference mesh"),
                          self.view)
        caption.Color = [0, 0, 0]
        caption.FontSize = 14
        caption.WindowLocation = "Lower Right Corner"

    def frame_camera(self, bounds):
        centre = [(bounds[2 * i] + bounds[2 * i + 1]) / 2 for i in range(3)]
        if bounds[5] - bounds[4] > 1e-12:  # 3D: an oblique view from the front
            self.view.CameraFocalPoint = centre
            self.view.CameraPosition = [c + d for c, d in zip(centre, self.camera)]
            self.view.CameraViewUp = self.up
            self.view.ResetCamera(False)  # fits the bounding sphere: wide rows of bodies end up small
            pv.GetActiveCamera().Dolly(self.zoom)
            return
        # 2D: fill the picture with the bounds of both meshes and the obstacles.
        self.view.InteractionMode = "2D"
        self.view.CameraFocalPoint = centre
        self.view.CameraPosition = [centre[0], centre[1], centre[2] + 10]
        self.view.CameraViewUp = [0, 1, 0]
        aspect = self.view.ViewSize[0] / self.view.ViewSize[1]
        half_height = max(bounds[3] - bounds[2], (bounds[1] - bounds[0]) / aspect) / 2
        self.view.CameraParallelScale = 1.08 * half_height

    def save(self, frame, path):
        time = self.times[frame]
        self.view.ViewTime = time
        self.clock.Text = "t = %.4g" % time
        pv.Render(self.view)
        pv.SaveScreenshot(path, self.view, ImageResolution=list(self.view.ViewSize))


def write_gif(frames, path, seconds_per_frame=0.08):
    try:
        from PIL import Image
    except ImportError:
        print("render: no PIL here, so no animation.gif (the PNG frames are written)")
        return
    def small(image, width=640):  # a GIF of full-size frames weighs tens of megabytes
        height = round(image.height * width / image.width)
        return image.resize((width, height)) if image.width > width else image

    images = [small(Image.open(f).convert("RGB")).convert("P", palette=Image.ADAPTIVE) for f in frames]
    images[0].save(path, save_all=True, append_images=images[1:], loop=0,
                   duration=int(1000 * seconds_per_frame))


def main():
    args = parse_arguments()
    if not os.path.exists(os.path.join(args.run_dir, "solution.pvd")):
        sys.exit("render: %s has no solution.pvd (not a ritr output directory?)" % args.run_dir)
    out = args.out or os.path.join(args.run_dir, "pictures")
    os.makedirs(out, exist_ok=True)
    scene = Scene(args.run_dir, args.field, args.size, args.camera, args.up, args.zoom)
    count = len(scene.times)
    for frame in args.frames:
        if not -count <= frame < count:
            sys.exit("render: frame %d does not exist (the run has %d frames)" % (frame, count))
        path = os.path.join(out, "figure-%05d.png" % (frame % count))
        scene.save(frame % count, path)
        print("render: wrote", path)
    if not args.no_animation:
        frames_dir = os.path.join(out, "animation")
        os.makedirs(frames_dir, exist_ok=True)
        frames = [os.path.join(frames_dir, "frame-%05d.png" % i) for i in range(count)]
        for i, path in enumerate(frames):
            scene.save(i, path)
        write_gif(frames, os.path.join(out, "animation.gif"))
        print("render: wrote %d frames and the GIF in %s" % (count, out))


if __name__ == "__main__":
    main()
