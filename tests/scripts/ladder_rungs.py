#!/usr/bin/python3
"""The ladder's rungs: refinement adds to each body's `refinements`, `--fixed-subdivide M`
multiplies each body's `subdivisions` (scripts/ladder.py, rung_overrides)."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from ladder import rung_overrides  # noqa: E402

SCENE = """
subsection Body 0
  set subdivisions = 70, 9
  set refinements  = 1
end
subsection Body 1
  set subdivisions = 4, 5, 6
end
"""


class RungOverrides(unittest.TestCase):
    def test_refinement_adds_to_each_body(self):
        o = rung_overrides(SCENE, 2, adaptivity=False)
        self.assertEqual(o["Adaptivity/enabled"], "false")
        self.assertEqual(o["Body 0/refinements"], "3")
        self.assertEqual(o["Body 1/refinements"], "2")
        self.assertNotIn("Body 0/subdivisions", o)

    def test_subdivide_multiplies_each_count(self):
        o = rung_overrides(SCENE, 0, adaptivity=True, factor=3)
        self.assertEqual(o["Adaptivity/enabled"], "true")
        self.assertEqual(o["Body 0/subdivisions"], "210, 27")
        self.assertEqual(o["Body 1/subdivisions"], "12, 15, 18")
        self.assertEqual(o["Body 0/refinements"], "1")

    def test_subdivide_needs_subdivisions(self):
        with self.assertRaises(SystemExit):
            rung_overrides("subsection Body 0\n  set mesh file = a.msh\nend\n", 0, False, factor=5)


if __name__ == "__main__":
    unittest.main()
