#!/usr/bin/python3
"""The ladder's headline over draws (`--draws`): r-ITR judged by the mean distance of its run and of
the variants that repeat it under perturbations at round-off, at its own run's time
(scripts/ladder.py, over_draws and hausdorff_headline)."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from ladder import hausdorff_headline, over_draws  # noqa: E402


def run(name, distance, seconds, vertices=100, adaptivity=True, exit_code=0):
    r = dict(name=name, total_wall_seconds=seconds, wall_seconds=seconds, n_vertices=vertices, adaptivity=adaptivity,
             exit_code=exit_code, peak_rss_bytes=2_000_000)
    if distance is not None:
        r["mean_hausdorff"] = distance
    return r


def ladder():
    """r-ITR (a lucky draw, 0.02, 10 s), two more draws (0.05 and 0.08), three fixed rungs and a reference."""
    return [run("ritr", 0.02, 10.0),
            run("fixed_r0", 0.06, 1.0, 100, False), run("fixed_r1", 0.04, 4.0, 400, False),
            run("fixed_r2", 0.01, 16.0, 1600, False), run("fixed_r3", None, 64.0, 6400, False),
            run("ritr_perturbed", 0.05, 30.0), run("ritr_perturbed2", 0.08, 30.0)]


class OverDraws(unittest.TestCase):
    def test_the_mean_over_the_run_and_its_draws_at_the_runs_time(self):
        runs = ladder()
        ritr, drawn = over_draws(runs[0], runs, ["ritr_perturbed", "ritr_perturbed2"])
        self.assertAlmostEqual(ritr["mean_hausdorff"], 0.05, places=15)
        self.assertEqual(ritr["total_wall_seconds"], 10.0)
        self.assertEqual(drawn, ["ritr", "ritr_perturbed", "ritr_perturbed2"])
        self.assertEqual(runs[0]["mean_hausdorff"], 0.02)  # the run itself keeps its own figure

    def test_without_draws_the_run_alone(self):
        runs = ladder()
        ritr, drawn = over_draws(runs[0], runs, [])
        self.assertIs(ritr, runs[0])
        self.assertEqual(drawn, [])

    def test_a_failed_draw_is_left_out_of_the_mean(self):
        runs = ladder()
        runs[-1].update(exit_code=3)
        ritr, drawn = over_draws(runs[0], runs, ["ritr_perturbed", "ritr_perturbed2"])
        self.assertAlmostEqual(ritr["mean_hausdorff"], 0.035, places=15)
        self.assertEqual(drawn, ["ritr", "ritr_perturbed"])

    def test_an_unknown_draw_is_an_error(self):
        runs = ladder()
        with self.assertRaises(ValueError):
            over_draws(runs[0], runs, ["ritr_perturbed9"])


class HeadlineOverDraws(unittest.TestCase):
    def test_the_lucky_draw_alone_matches_a_finer_rung_than_the_mean(self):
        runs = ladder()
        alone = hausdorff_headline(runs, runs[4], 0)
        self.assertEqual(alone["matching_fixed"], "fixed_r2")
        self.assertNotIn("draws", alone)
        drawn = hausdorff_headline(runs, runs[4], 0, ["ritr_perturbed", "ritr_perturbed2"])
        # The mean, 0.05, lies between the 100- and 400-vertex rungs: the coarsest rung as accurate
        # is the 400-vertex one, the finest r-ITR is as accurate as the 100-vertex one; the ratios
        # take the scene's run's 10 s.
        self.assertEqual(drawn["matching_fixed"], "fixed_r1")
        self.assertAlmostEqual(drawn["time_ratio_ritr_to_fixed"], 2.5, places=12)
        self.assertEqual(drawn["draws"], ["ritr", "ritr_perturbed", "ritr_perturbed2"])
        self.assertAlmostEqual(drawn["ritr_mean_hausdorff"], 0.05, places=15)
        self.assertEqual(drawn["time_to_accuracy"]["matched"], "fixed_r0")
        self.assertAlmostEqual(drawn["time_to_accuracy"]["time_ratio"], 10.0, places=12)
        self.assertEqual(alone["time_to_accuracy"]["matched"], "fixed_r1")


if __name__ == "__main__":
    unittest.main()
