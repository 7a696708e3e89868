#!/usr/bin/python3
"""The reference mesh of a run's frame as a gmsh file, so that another run can be built on it.

    scripts/frame_mesh.py RUN/solution-NNNNN.vtu OUT.msh

Writes the frame's cells at their reference positions (point data `reference_position`: for an
r-ITR run, the moved mesh of that step) in gmsh's ASCII format 2.2, each cell's physical tag its
`material_id`, no boundary elements (boundary ids 0). A body with `shape = file` on OUT.msh,
refined with `refinements`, and `start from` the same frame gives a fixed mesh that starts from
exactly the frame's state, every fine cell inside one of the frame's cells (doc/parameters.md,
Starting from another run's frame).
"""
import sys

from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkObject
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

GMSH_TYPE = {3: (1, 2), 5: (2, 3), 10: (4, 4)}  # VTK line, triangle, tetrahedron -> gmsh type, nodes


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().split("\n\n")[1].strip())
    frame, out = sys.argv[1:]
    vtkObject.GlobalWarningDisplayOff()  # a bad file is reported in one line below
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(frame)
    reader.Update()
    grid = reader.GetOutput()
    reference = grid.GetPointData().GetArray("reference_position")
    materials = grid.GetCellData().GetArray("material_id")
    if grid.GetNumberOfCells() == 0 or reference is None or materials is None:
        print(f"frame_mesh: {frame}: not a frame of a ritr run (no cells, reference_position or material_id)",
              file=sys.stderr)
        sys.exit(2)
    points = vtk_to_numpy(reference)
    material = vtk_to_numpy(materials)
    with open(out, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n%d\n" % len(points))
        for i, p in enumerate(points):
            f.write("%d %.17g %.17g %.17g\n" % (i + 1, p[0], p[1], p[2]))
        f.write("$EndNodes\n$Elements\n%d\n" % grid.GetNumberOfCells())
        for c in range(grid.GetNumberOfCells()):
            kind, count = GMSH_TYPE[grid.GetCellType(c)]
            ids = grid.GetCell(c).GetPointIds()
            nodes = " ".join(str(ids.GetId(k) + 1) for k in range(count))
            f.write("%d %d 2 %d 1 %s\n" % (c + 1, kind, int(material[c]), nodes))
        f.write("$EndElements\n")


if __name__ == "__main__":
    main()
