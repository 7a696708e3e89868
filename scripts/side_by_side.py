#!/usr/bin/python3
"""Several 2D runs of one scene side by side at the same times: one column per run, one row per
time, the deformed bodies coloured by speed, with mesh edges (for meshes of at most --edges-below
vertices) and the obstacles. For seeing where runs part (doc/benchmarks.md, masticator).

    scripts/side_by_side.py --times 4.4 4.8 5.2 --out FIGURE.png NAME=RUN_DIR [NAME=RUN_DIR ...]

Each time picks the run's output frame nearest to it (solution.pvd and obstacles.pvd). Plain
matplotlib on VTK's XML reader; scripts/render.py draws one run with ParaView instead.
"""
import argparse
import os
import sys

import matplotlib
import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from frame_metrics import cells, points, read_frame, series  # noqa: E402
from vtkmodules.util.numpy_support import vtk_to_numpy  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def nearest(frames, time):
    return min(frames, key=lambda frame: abs(frame[0] - time))


def speeds(grid):
    return numpy.linalg.norm(vtk_to_numpy(grid.GetPointData().GetArray("velocity")), axis=1)


def draw(ax, directory, frame_time, body, edges_below, speed_limit):
    xy, triangles = points(body), cells(body)
    shading = ax.tripcolor(xy[:, 0], xy[:, 1], triangles, speeds(body), shading="gouraud", vmin=0, vmax=speed_limit)
    if len(xy) <= edges_below:
        ax.triplot(xy[:, 0], xy[:, 1], triangles, linewidth=0.2, color="white")
    if os.path.exists(os.path.join(directory, "obstacles.pvd")):
        obstacles = read_frame(nearest(series(directory, "obstacles"), frame_time)[1])
        corners = points(obstacles)
        for cell in cells(obstacles):
            ax.fill(corners[cell, 0], corners[cell, 1], color="0.65")
    return shading


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("runs", nargs="+", metavar="NAME=RUN_DIR")
    p.add_argument("--times", type=float, nargs="+", required=True)
    p.add_argument("--out", required=True, help="the PNG to write")
    p.add_argument("--edges-below", type=int, default=5000, help="draw the edges of meshes up to this many vertices")
    p.add_argument("--speed-limit", type=float, default=None, help="top of the colour scale (default: the largest speed)")
    p.add_argument("--box", type=float, nargs=4, metavar=("XMIN", "XMAX", "YMIN", "YMAX"))
    args = p.parse_args()
    runs = [r.split("=", 1) for r in args.runs]
    if any(len(r) != 2 for r in runs):
        p.error("each run is NAME=RUN_DIR")
    # frames[i][j]: (time, grid) of run j's frame nearest to time i, each read once.
    frames = []
    for time in args.times:
        nearest_frames = [nearest(series(directory), time) for _, directory in runs]
        frames.append([(t, read_frame(path)) for t, path in nearest_frames])
    limit = args.speed_limit
    if limit is None:
        limit = max(speeds(grid).max() for row in frames for _, grid in row)
    fig, axes = plt.subplots(len(args.times), len(runs), figsize=(4.2 * len(runs), 2.1 * len(args.times)),
                             squeeze=False, layout="constrained")
    for row, row_frames in zip(axes, frames):
        for ax, (name, directory), (frame_time, body) in zip(row, runs, row_frames):
            shading = draw(ax, directory, frame_time, body, args.edges_below, limit)
            ax.set_title(f"{name}, t = {frame_time:.3g}", fontsize=8)
            ax.set_aspect("equal")
            if args.box:
                ax.set_xlim(*args.box[:2])
                ax.set_ylim(*args.box[2:])
            ax.set_xticks([])
            ax.set_yticks([])
    fig.colorbar(shading, ax=axes, shrink=0.6, label="speed")
    fig.savefig(args.out, dpi=100)
    return 0


if __name__ == "__main__":
    sys.exit(main())
