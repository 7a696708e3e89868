"""Measurements on the output frames of a ritr run (VTK's XML readers), for scripts/ladder.py.

lowest_point: the lowest deformed height (y) of the bodies, to tell whether a run passed a gap.
corner_distances: for each obstacle vertex that touches a body (within `touch` of its deformed
boundary), the distance to the nearest deformed mesh vertex; small when the mesh has put a
vertex on the obstacle's corner, about half an edge when the corner presses into an edge (the
paper's stamping figure). 2D only.
centroid_heights: the height of the bodies' deformed area centroid in every output frame, with
the frame's time (the paper's varying-friction figure). 2D only.
kinetic_energies: the bodies' kinetic energy in every output frame, with the frame's time; it
shows a coarse run storing and releasing energy that the fine one does not (the masticator).
end_heights: the mean deformed height (y) of the material on the bodies' leftmost and rightmost
reference ends in every output frame, with the frame's time: when a bar's ends come off the
teeth (the masticator). 2D only.
"""
import glob
import os
import xml.etree.ElementTree

import numpy
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkFiltersCore import vtkFeatureEdges
from vtkmodules.vtkFiltersGeometry import vtkGeometryFilter
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader


def read_frame(path):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def last_frame(directory, prefix):
    return read_frame(sorted(glob.glob(os.path.join(directory, prefix + "-*.vtu")))[-1])


def points(grid):
    return vtk_to_numpy(grid.GetPoints().GetData())[:, :2]


def lowest_point(directory):
    return float(points(last_frame(directory, "solution"))[:, 1].min())


def boundary_segments(grid):
    """(n, 2, 2) array of the end points of the boundary edges of a 2D triangle mesh."""
    surface = vtkGeometryFilter()
    surface.SetInputData(grid)
    edges = vtkFeatureEdges()
    edges.SetInputConnection(surface.GetOutputPort())
    edges.BoundaryEdgesOn()
    edges.FeatureEdgesOff()
    edges.NonManifoldEdgesOff()
    edges.ManifoldEdgesOff()
    edges.Update()
    lines = edges.GetOutput()
    xy = vtk_to_numpy(lines.GetPoints().GetData())[:, :2]
    ids = vtk_to_numpy(lines.GetLines().GetConnectivityArray()).reshape(-1, 2)
    return xy[ids]


def distance_to_segments(p, segments):
    a, b = segments[:, 0], segments[:, 1]
    ab = b - a
    t = numpy.clip(numpy.einsum("ij,ij->i", p - a, ab) / numpy.einsum("ij,ij->i", ab, ab), 0.0, 1.0)
    return numpy.linalg.norm(a + t[:, None] * ab - p, axis=1).min()


def corner_distances(directory, touch):
    body = last_frame(directory, "solution")
    vertices, segments = points(body), boundary_segments(body)
    corners = [c for c in points(last_frame(directory, "obstacles")) if distance_to_segments(c, segments) <= touch]
    return [float(numpy.linalg.norm(vertices - c, axis=1).min()) for c in corners]


def series(directory, name="solution"):
    """[(time, path), ...] of the frames of a run's NAME.pvd."""
    collection = xml.etree.ElementTree.parse(os.path.join(directory, name + ".pvd")).getroot()
    return [(float(d.get("timestep")), os.path.join(directory, d.get("file"))) for d in collection.iter("DataSet")]


def over_frames(directory, measure):
    """[[time, measure(frame)], ...] over the frames of solution.pvd."""
    return [[time, measure(read_frame(path))] for time, path in series(directory)]


def cells(grid):
    """(cells, vertices per cell) array of a grid's connectivity (one cell type)."""
    connectivity = vtk_to_numpy(grid.GetCells().GetConnectivityArray())
    return connectivity.reshape(grid.GetNumberOfCells(), -1)


def simplex_measures(xyz, simplices):
    """Signed area (triangles) or volume (tetrahedra) of each simplex with vertices xyz[simplices]."""
    corners = [xyz[i] for i in simplices.T]
    edges = [c - corners[0] for c in corners[1:]]
    if simplices.shape[1] == 3:
        return 0.5 * (edges[0][:, 0] * edges[1][:, 1] - edges[0][:, 1] * edges[1][:, 0])
    return numpy.einsum("ij,ij->i", edges[0], numpy.cross(edges[1], edges[2])) / 6


def centroid_height(grid):
    """Height (y) of the centroid of a triangle (2D) or tetrahedron (3D) mesh, weighted by
    cell area or volume."""
    xyz, simplices = vtk_to_numpy(grid.GetPoints().GetData()), cells(grid)
    measure = simplex_measures(xyz, simplices)
    return float((xyz[simplices][:, :, 1].mean(axis=1) * measure).sum() / measure.sum())


def centroid_heights(directory):
    """[[time, centroid height], ...] over the frames of solution.pvd."""
    return over_frames(directory, centroid_height)


def kinetic_energy(grid, densities):
    """Kinetic energy 1/2 v^T M v of a frame with the consistent P1 mass matrix of its reference
    cells (M_ij = rho |cell| (1 + delta_ij) / ((d + 1)(d + 2)) on each simplex), which is exact for
    velocities linear in each cell. `densities`: {material id: density}."""
    simplices = cells(grid)
    n = simplices.shape[1]
    reference = vtk_to_numpy(grid.GetPointData().GetArray("reference_position"))
    measure = numpy.abs(simplex_measures(reference, simplices))
    velocity = vtk_to_numpy(grid.GetPointData().GetArray("velocity"))[simplices]  # (cells, corners, 3)
    material = vtk_to_numpy(grid.GetCellData().GetArray("material_id")).astype(int)
    rho = numpy.array([densities[m] for m in material])
    # v^T M v on a cell = rho |cell| / ((d+1)(d+2)) * (sum_i |v_i|^2 + |sum_i v_i|^2).
    quadratic = (velocity ** 2).sum(axis=(1, 2)) + (velocity.sum(axis=1) ** 2).sum(axis=1)
    return float(0.5 * (rho * measure * quadratic).sum() / (n * (n + 1)))


def kinetic_energies(directory, densities):
    """[[time, kinetic energy], ...] over the frames of solution.pvd (see kinetic_energy)."""
    return over_frames(directory, lambda grid: kinetic_energy(grid, densities))


def end_height(grid):
    """(left, right): the mean deformed height of the vertices whose reference x is the least /
    the greatest (a bar's two end faces; r-ITR may slide them along the face, not off it)."""
    reference = vtk_to_numpy(grid.GetPointData().GetArray("reference_position"))[:, 0]
    y = points(grid)[:, 1]
    tolerance = 1e-9 * (reference.max() - reference.min())
    return [float(y[reference <= reference.min() + tolerance].mean()),
            float(y[reference >= reference.max() - tolerance].mean())]


def end_heights(directory):
    """[[time, left end height, right end height], ...] over the frames of solution.pvd."""
    return [[time, *heights] for time, heights in over_frames(directory, end_height)]
