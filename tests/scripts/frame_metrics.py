#!/usr/bin/python3
"""Measurements on output frames (scripts/frame_metrics.py) against values computed by hand.
Kinetic energy: a rigidly spinning square (1/2 rho w^2 J, J = 1/6 for the unit square about its
centre), a translating cube of tetrahedra (1/2 rho V |v|^2) and two materials of different density.
End heights: a bar sheared so that its ends move by known heights, on a mesh whose end faces carry
vertices at different heights."""
import os
import sys
import tempfile
import unittest

import numpy
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkPoints
from vtkmodules.vtkCommonDataModel import VTK_TETRA, VTK_TRIANGLE, vtkUnstructuredGrid
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridWriter

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from frame_metrics import end_height, end_heights, kinetic_energies, kinetic_energy  # noqa: E402


def grid(reference, deformed, cells, cell_type, velocity, material):
    g = vtkUnstructuredGrid()
    points = vtkPoints()
    points.SetData(numpy_to_vtk(numpy.asarray(deformed, dtype=float), deep=True))
    g.SetPoints(points)
    for c in cells:
        g.InsertNextCell(cell_type, len(c), [int(i) for i in c])
    for name, values in (("reference_position", reference), ("velocity", velocity)):
        array = numpy_to_vtk(numpy.asarray(values, dtype=float), deep=True)
        array.SetName(name)
        g.GetPointData().AddArray(array)
    ids = numpy_to_vtk(numpy.asarray(material, dtype=float), deep=True)
    ids.SetName("material_id")
    g.GetCellData().AddArray(ids)
    return g


def square_grid(n, velocity_of, material_of=lambda centre: 0):
    """The unit square centred at the origin in n x n squares, each cut into two triangles; the
    deformed points are the reference ones shifted (kinetic energy reads the reference cells)."""
    s = numpy.linspace(-0.5, 0.5, n + 1)
    reference = numpy.array([[x, y, 0.0] for y in s for x in s])
    cells = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            cells += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
    material = [material_of(reference[list(c)].mean(axis=0)) for c in cells]
    return grid(reference, reference + [3.0, -1.0, 0.0], cells, VTK_TRIANGLE,
                [velocity_of(p) for p in reference], material)


def write_series(directory, grids):
    """solution-K.vtu for each grid and a solution.pvd that lists them at times 0, 0.5, 1, ..."""
    entries = []
    for k, g in enumerate(grids):
        writer = vtkXMLUnstructuredGridWriter()
        writer.SetFileName(os.path.join(directory, f"solution-{k:05d}.vtu"))
        writer.SetInputData(g)
        writer.Write()
        entries.append(f'<DataSet timestep="{0.5 * k}" file="solution-{k:05d}.vtu"/>')
    with open(os.path.join(directory, "solution.pvd"), "w") as f:
        f.write('<VTKFile type="Collection"><Collection>' + "".join(entries) + "</Collection></VTKFile>")


def bar_grid(left_drop, right_drop, nx=8, ny=3):
    """The bar [-2, 2] x [-0.25, 0.25] in nx x ny squares cut into triangles, its deformed points
    moved down by left_drop at x = -2 and right_drop at x = 2, linearly in between."""
    xs, ys = numpy.linspace(-2, 2, nx + 1), numpy.linspace(-0.25, 0.25, ny + 1)
    reference = numpy.array([[x, y, 0.0] for y in ys for x in xs])
    drop = left_drop + (reference[:, 0] + 2) / 4 * (right_drop - left_drop)
    deformed = reference - numpy.outer(drop, [0.0, 1.0, 0.0])
    cells = []
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            cells += [(a, a + 1, a + nx + 2), (a, a + nx + 2, a + nx + 1)]
    return grid(reference, deformed, cells, VTK_TRIANGLE, numpy.zeros_like(reference), [0] * len(cells))


class EndHeights(unittest.TestCase):
    def test_a_sheared_bar(self):
        # The end faces' vertices sit at y = -0.25 ... 0.25, symmetric about 0: their mean is the drop.
        left, right = end_height(bar_grid(1.2, -0.3))
        self.assertAlmostEqual(left, -1.2, places=12)
        self.assertAlmostEqual(right, 0.3, places=12)

    def test_series_follows_the_pvd(self):
        with tempfile.TemporaryDirectory() as d:
            write_series(d, [bar_grid(0.0, 0.0), bar_grid(0.5, 0.0), bar_grid(1.0, 2.0)])
            series = end_heights(d)
        self.assertEqual([row[0] for row in series], [0.0, 0.5, 1.0])
        for row, expected in zip(series, ([0.0, 0.0], [-0.5, 0.0], [-1.0, -2.0])):
            self.assertAlmostEqual(row[1], expected[0], places=12)
            self.assertAlmostEqual(row[2], expected[1], places=12)


class KineticEnergy(unittest.TestCase):
    def test_spinning_square(self):
        w, rho = 2.5, 700.0
        g = square_grid(4, lambda p: [-w * p[1], w * p[0], 0.0])
        self.assertAlmostEqual(kinetic_energy(g, {0: rho}), 0.5 * rho * w ** 2 / 6, places=10)

    def test_translating_cube_of_tetrahedra(self):
        corners = numpy.array([[x, y, z] for z in (0, 2) for y in (0, 2) for x in (0, 2)], dtype=float)
        # The cube's six tetrahedra around its diagonal 0-7.
        cells = [(0, 1, 3, 7), (0, 3, 2, 7), (0, 2, 6, 7), (0, 6, 4, 7), (0, 4, 5, 7), (0, 5, 1, 7)]
        v = [1.0, -2.0, 0.5]
        g = grid(corners, corners, cells, VTK_TETRA, [v] * 8, [0] * 6)
        self.assertAlmostEqual(kinetic_energy(g, {0: 3.0}), 0.5 * 3.0 * 8.0 * numpy.dot(v, v), places=10)

    def test_two_materials(self):
        # Left half density 1000, right half 10, both translating at speed 2: 1/2 (500 + 5) 4.
        g = square_grid(4, lambda p: [2.0, 0.0, 0.0], lambda centre: 0 if centre[0] < 0 else 1)
        self.assertAlmostEqual(kinetic_energy(g, {0: 1000.0, 1: 10.0}), 0.5 * 505.0 * 4.0, places=9)

    def test_series_follows_the_pvd(self):
        with tempfile.TemporaryDirectory() as d:
            write_series(d, [square_grid(2, lambda p, s=speed: [0.0, s, 0.0]) for speed in (0.0, 1.0, 3.0)])
            series = kinetic_energies(d, {0: 2.0})
        self.assertEqual([t for t, _ in series], [0.0, 0.5, 1.0])
        for (_, e), speed in zip(series, (0.0, 1.0, 3.0)):
            self.assertAlmostEqual(e, speed ** 2, places=10)


if __name__ == "__main__":
    unittest.main()
