#!/usr/bin/python3
"""Kinetic energy of an output frame (scripts/frame_metrics.py, kinetic_energy) against values
computed by hand: a rigidly spinning square (1/2 rho w^2 J, J = 1/6 for the unit square about its
centre), a translating cube of tetrahedra (1/2 rho V |v|^2) and two materials of different density."""
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
from frame_metrics import kinetic_energies, kinetic_energy  # noqa: E402


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
            entries = []
            for k, speed in enumerate((0.0, 1.0, 3.0)):
                writer = vtkXMLUnstructuredGridWriter()
                writer.SetFileName(os.path.join(d, f"solution-{k:05d}.vtu"))
                writer.SetInputData(square_grid(2, lambda p: [0.0, speed, 0.0]))
                writer.Write()
                entries.append(f'<DataSet timestep="{0.5 * k}" file="solution-{k:05d}.vtu"/>')
            with open(os.path.join(d, "solution.pvd"), "w") as f:
                f.write('<VTKFile type="Collection"><Collection>' + "".join(entries) + "</Collection></VTKFile>")
            series = kinetic_energies(d, {0: 2.0})
        self.assertEqual([t for t, _ in series], [0.0, 0.5, 1.0])
        for (_, e), speed in zip(series, (0.0, 1.0, 3.0)):
            self.assertAlmostEqual(e, speed ** 2, places=10)


if __name__ == "__main__":
    unittest.main()
