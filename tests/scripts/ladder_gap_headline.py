#!/usr/bin/python3
"""The ladder's headline on a scene with a gap (`--pass-below`): r-ITR that passes is set against
the coarsest fixed rung that passes, even when locked rungs are closer to the reference, and its
distances stay beside that (scripts/ladder.py, gap_headline)."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from ladder import further_than_every_rung, gap_headline  # noqa: E402


def run(name, passes, distance, seconds, vertices, adaptivity=False):
    r = dict(name=name, passes=passes, total_wall_seconds=seconds, wall_seconds=seconds, n_vertices=vertices,
             adaptivity=adaptivity, exit_code=0, peak_rss_bytes=3_000_000)
    if distance is not None:
        r["mean_hausdorff"] = distance
    return r


def ladder(ritr_passes=True, reference_passes=True, r2_passes=False):
    """r-ITR (passes, but further from the reference than the locked rungs), three rungs that lock
    (or the third passes) and a reference that passes."""
    return [run("ritr", ritr_passes, 0.11, 8.0, 167, adaptivity=True),
            run("fixed_r0", False, 0.08, 2.0, 167), run("fixed_r1", False, 0.06, 14.0, 943),
            run("fixed_r2", r2_passes, 0.04, 250.0, 6161), run("fixed_r3", reference_passes, None, 16000.0, 44113)]


class GapHeadline(unittest.TestCase):
    def test_r_itr_that_passes_is_set_against_the_first_rung_that_passes(self):
        runs = ladder()
        head = gap_headline(runs, runs[-1], 1_000_000)
        self.assertEqual(head["matching_fixed"], "fixed_r3")
        self.assertAlmostEqual(head["time_ratio_ritr_to_fixed"], 8.0 / 16000.0, places=15)
        self.assertAlmostEqual(head["vertex_ratio"], 44113 / 167, places=12)
        self.assertIn("passes", head["why"])
        # The distances say what they say: every locked rung is closer than r-ITR.
        self.assertIsNone(head["time_to_accuracy"]["matched"])
        self.assertIn("0.11", head["time_to_accuracy"]["sentence"])
        self.assertTrue(further_than_every_rung(head))

    def test_r_itr_closer_than_a_locked_rung_is_not_further_than_every_rung(self):
        runs = ladder()
        runs[0]["mean_hausdorff"] = 0.05
        head = gap_headline(runs, runs[-1], 1_000_000)
        self.assertEqual(head["matching_fixed"], "fixed_r3")
        self.assertEqual(head["time_to_accuracy"]["matched"], "fixed_r1")
        self.assertFalse(further_than_every_rung(head))
        self.assertFalse(further_than_every_rung({"matching_fixed": None, "why": "no reference"}))

    def test_the_coarsest_passing_rung_not_the_reference(self):
        runs = ladder(r2_passes=True)
        head = gap_headline(runs, runs[-1], 1_000_000)
        self.assertEqual(head["matching_fixed"], "fixed_r2")
        self.assertAlmostEqual(head["time_ratio_ritr_to_fixed"], 8.0 / 250.0, places=15)

    def test_a_failed_reference_says_so(self):
        runs = ladder()
        runs[-1].update(exit_code=3, passes=None)
        head = gap_headline(runs, runs[-1], 1_000_000)
        self.assertIsNone(head["matching_fixed"])
        self.assertIn("did not finish", head["why"])

    def test_a_reference_that_locks_gives_no_comparison(self):
        runs = ladder(reference_passes=False)
        head = gap_headline(runs, runs[-1], 1_000_000)
        self.assertIsNone(head["matching_fixed"])
        self.assertIn("locks", head["why"])

    def test_r_itr_that_locks_is_judged_by_its_distance(self):
        runs = ladder(ritr_passes=False)
        head = gap_headline(runs, runs[-1], 1_000_000)
        self.assertEqual(head["matching_fixed"], "fixed_r0")
        self.assertIn("Hausdorff", head["why"])


if __name__ == "__main__":
    unittest.main()
