"""Opens every output of a short ritr run in ParaView (pvbatch) and checks what a user sees:
the frame count of each collection, the arrays of the output contract and their ranges.

    pvbatch check_outputs.py RUN_DIR FRAMES

Prints one line per failed check and exits 1 if there is any."""
import sys

import numpy
from paraview import servermanager, simple
from vtkmodules.util.numpy_support import vtk_to_numpy

POINT_ARRAYS = {"displacement": 3, "velocity": 3, "reference_position": 3, "contact_force": 3,
                "contact_pressure": 1}
CELL_ARRAYS = {"strain": 1, "von_mises_stress": 1, "material_id": 1, "element_quality": 1}

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def frames(collection):
    """The datasets of a .pvd collection as ParaView reads them, one per time step."""
    reader = simple.PVDReader(FileName=collection)
    times = list(reader.TimestepValues)
    data = []
    for t in times:
        reader.UpdatePipeline(t)
        grid = servermanager.Fetch(reader)
        data.append(grid.NewInstance())
        data[-1].DeepCopy(grid)
    return times, data


def arrays(attributes):
    return {attributes.GetArrayName(i): vtk_to_numpy(attributes.GetArray(i))
            for i in range(attributes.GetNumberOfArrays())}


def check_mesh_series(name, run_dir, n_frames):
    times, data = frames("%s/%s.pvd" % (run_dir, name))
    check(len(times) == n_frames, "%s.pvd has %d frames, not %d" % (name, len(times), n_frames))
    check(times == sorted(times) and len(set(times)) == len(times), name + ".pvd: times not increasing")
    series = []
    for t, grid in zip(times, data):
        where = "%s at t = %g" % (name, t)
        points, cells = arrays(grid.GetPointData()), arrays(grid.GetCellData())
        for wanted, observed, size in ((POINT_ARRAYS, points, grid.GetNumberOfPoints()),
                                       (CELL_ARRAYS, cells, grid.GetNumberOfCells())):
            check(set(observed) == set(wanted), "%s: arrays %s, expected %s"
                  % (where, sorted(observed), sorted(wanted)))
            for array, components in wanted.items():
                if array in observed:
                    values = observed[array].reshape(size, -1)
                    check(values.shape[1] == components, "%s: %s has %d components"
                          % (where, array, values.shape[1]))
                    check(numpy.isfinite(values).all(), "%s: %s is not finite" % (where, array))
        if set(points) != set(POINT_ARRAYS) or set(cells) != set(CELL_ARRAYS):
            continue
        xyz = vtk_to_numpy(grid.GetPoints().GetData())
        check(numpy.all(cells["strain"] >= 0), where + ": negative strain")
        check(numpy.all(cells["von_mises_stress"] >= 0), where + ": negative von Mises stress")
        check(numpy.all((cells["element_quality"] > 0) & (cells["element_quality"] <= 1 + 1e-12)),
              where + ": element_quality outside (0, 1]")
        check(numpy.all(cells["material_id"] == 0), where + ": material_id is not 0")
        # The points are the deformed positions (solution) or the reference ones (reference).
        expected = points["reference_position"] + (points["displacement"] if name == "solution" else 0)
        check(numpy.allclose(xyz, expected, rtol=0, atol=1e-12),
              where + ": points do not match reference_position (+ displacement)")
        series.append((points, cells))
    return series


def main():
    run_dir, n_frames = sys.argv[1], int(sys.argv[2])
    solution = check_mesh_series("solution", run_dir, n_frames)
    reference = check_mesh_series("reference", run_dir, n_frames)
    if len(solution) == n_frames and len(reference) == n_frames:
        first, last = solution[0], solution[-1]
        check(numpy.abs(first[0]["displacement"]).max() == 0, "solution starts displaced")
        check(numpy.abs(last[0]["displacement"]).max() > 1e-3, "the body did not move")
        check(last[0]["contact_pressure"].max() > 0, "no contact pressure at the end (the ball lands)")
        check(last[1]["von_mises_stress"].max() > 0, "no stress at the end")
        check(numpy.abs(last[0]["reference_position"] - first[0]["reference_position"]).max() > 1e-6,
              "r-adaptivity did not move the reference mesh")
    times, data = frames(run_dir + "/obstacles.pvd")
    check(len(times) == n_frames, "obstacles.pvd has %d frames, not %d" % (len(times), n_frames))
    check(all(d.GetNumberOfCells() > 0 for d in data), "an obstacles frame has no cells")
    print("checked %d frames of solution, reference and obstacles: %s"
          % (n_frames, "%d failures" % len(failures) if failures else "all good"))
    sys.exit(1 if failures else 0)


main()
