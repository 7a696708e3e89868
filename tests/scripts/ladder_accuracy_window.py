#!/usr/bin/python3
"""The ladder's accuracy window (`--accuracy-until T`): mean and largest Hausdorff distance over
the frames up to time T only, a frame at T included despite round-off in its time
(scripts/ladder.py, hausdorff_until)."""
import os
import sys
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from ladder import hausdorff_until  # noqa: E402

FRAMES = [{"time": 0.0, "hausdorff": 0.0}, {"time": 0.2, "hausdorff": 0.03},
          {"time": 0.6000000000000001, "hausdorff": 0.06}, {"time": 0.8, "hausdorff": 0.9}]


class HausdorffUntil(unittest.TestCase):
    def test_frames_after_the_window_are_left_out(self):
        mean, largest = hausdorff_until(FRAMES, 0.6)
        self.assertAlmostEqual(mean, 0.03, places=15)
        self.assertEqual(largest, 0.06)

    def test_a_window_over_every_frame_is_the_whole_run(self):
        mean, largest = hausdorff_until(FRAMES, 10)
        self.assertAlmostEqual(mean, 0.2475, places=15)
        self.assertEqual(largest, 0.9)

    def test_no_frame_in_the_window(self):
        self.assertIsNone(hausdorff_until(FRAMES[1:], 0.1))


if __name__ == "__main__":
    unittest.main()
