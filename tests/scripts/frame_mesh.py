#!/usr/bin/python3
"""scripts/frame_mesh.py: a fixed mesh built on an r-ITR frame's moved reference mesh and refined,
started from that frame, starts from exactly the frame's state (every fine node on a frame node
or the midpoint of a frame edge, with the frame's piecewise-linear positions and velocities
there), and runs on. Usage: frame_mesh.py RITR_BINARY."""
import csv
import os
import subprocess
import sys
import tempfile
import unittest

from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(SOURCE, "scripts"))
from prm_variant import write_variant  # noqa: E402

RITR = sys.argv.pop(1) if len(sys.argv) > 1 else os.path.join(SOURCE, "build", "ritr")
SCENE = os.path.join(SOURCE, "prm", "ritr_ball_on_spikes_2d.prm")


def nodes(path):
    with open(path) as f:
        return [[float(row[k]) for k in ("u_x", "u_y", "x_x", "x_y", "v_x", "v_y")] for row in csv.DictReader(f)]


def edges(frame):
    reader = vtkXMLUnstructuredGridReader()
    reader.SetFileName(frame)
    reader.Update()
    grid = reader.GetOutput()
    found = set()
    for c in range(grid.GetNumberOfCells()):
        ids = grid.GetCell(c).GetPointIds()
        points = [ids.GetId(k) for k in range(ids.GetNumberOfIds())]
        found.update((a, b) for a in points for b in points if a <= b)
    return found


class FrameMesh(unittest.TestCase):
    def test_refined_frame_mesh_starts_from_the_frame_state(self):
        with tempfile.TemporaryDirectory() as work:
            ritr_run = os.path.join(work, "ritr")
            prm = write_variant(SCENE, {"output directory": ritr_run, "end time": "0.15", "output every": "5",
                                        "write nodal csv": "true"}, os.path.join(work, "ritr.prm"))
            subprocess.run([RITR, prm], check=True, capture_output=True)
            frame = os.path.join(ritr_run, "solution-00015.vtu")
            mesh = os.path.join(work, "frame.msh")
            subprocess.run([sys.executable, os.path.join(SOURCE, "scripts", "frame_mesh.py"), frame, mesh], check=True)

            fine_run = os.path.join(work, "fine")
            prm = write_variant(SCENE, {"output directory": fine_run, "end time": "0.17", "write nodal csv": "true",
                                        "Adaptivity/enabled": "false", "Body 0/shape": "file", "Body 0/file": mesh,
                                        "Body 0/refinements": "1", "start from": frame},
                                os.path.join(work, "fine.prm"))
            result = subprocess.run([RITR, prm], capture_output=True, text=True)
            self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
            self.assertIn("2 steps from t = 0.15", result.stdout)

            coarse = nodes(os.path.join(ritr_run, "nodes-00015.csv"))
            fine = nodes(os.path.join(fine_run, "nodes-00000.csv"))
            frame_edges = edges(frame)
            self.assertGreater(len(fine), 3 * len(coarse))
            largest, unmatched = 0.0, 0
            for f in fine:
                for a, b in frame_edges:
                    mid = [0.5 * (coarse[a][k] + coarse[b][k]) for k in range(6)]
                    if abs(f[0] - mid[0]) < 1e-12 and abs(f[1] - mid[1]) < 1e-12:
                        largest = max(largest, max(abs(f[k] - mid[k]) for k in range(2, 6)))
                        break
                else:
                    unmatched += 1
            self.assertEqual(unmatched, 0)
            self.assertLess(largest, 1e-12)

    def test_not_a_frame_is_refused(self):
        with tempfile.TemporaryDirectory() as work:
            empty = os.path.join(work, "empty.vtu")
            open(empty, "w").close()
            result = subprocess.run([sys.executable, os.path.join(SOURCE, "scripts", "frame_mesh.py"), empty,
                                     os.path.join(work, "out.msh")], capture_output=True, text=True)
            self.assertEqual(result.returncode, 2)
            self.assertEqual(result.stderr.strip().count("\n"), 0, result.stderr)
            self.assertIn("not a frame of a ritr run", result.stderr)
            self.assertFalse(os.path.exists(os.path.join(work, "out.msh")))


if __name__ == "__main__":
    unittest.main()
