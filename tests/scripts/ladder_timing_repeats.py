#!/usr/bin/python3
"""`ladder.py --timing-repeats N`: a short run is timed as the fastest of N runs, a long one once,
and a ladder that reuses the run keeps that fastest time (scripts/ladder.py, run_rung). A fake
program stands in for ritr: it writes the summary.json of a deterministic run whose own time is
the next of a list."""
import argparse
import json
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from ladder import run_rung  # noqa: E402

FAKE_RITR = """#!/usr/bin/python3
import json, os, sys
prm = open(sys.argv[1]).read()
directory = [l.split("=", 1)[1].strip() for l in prm.splitlines() if "output directory" in l][0]
counter = os.path.join(os.path.dirname(sys.argv[1]), "calls")
calls = int(open(counter).read()) if os.path.exists(counter) else 0
open(counter, "w").write(str(calls + 1))
times = [float(t) for t in os.environ["FAKE_TIMES"].split(",")]
os.makedirs(directory, exist_ok=True)
json.dump({"complete": True, "n_vertices": 9, "final_energy": -1.5, "total_wall_seconds": times[calls]},
          open(os.path.join(directory, "summary.json"), "w"))
sys.exit(1 if str(calls) in os.environ.get("FAKE_FAILS", "").split(",") else 0)
"""


class TimingRepeats(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.TemporaryDirectory()
        self.ritr = os.path.join(self.work.name, "fake_ritr")
        with open(self.ritr, "w") as f:
            f.write(FAKE_RITR)
        os.chmod(self.ritr, 0o755)
        self.scene = os.path.join(self.work.name, "scene.prm")
        with open(self.scene, "w") as f:
            f.write("set end time = 1\nset output directory = nowhere\n")

    def tearDown(self):
        self.work.cleanup()

    def run_it(self, times, reuse=False, quick=False, fails=(), repeats=3):
        os.environ["FAKE_TIMES"] = ",".join(map(str, times))
        os.environ["FAKE_FAILS"] = ",".join(map(str, fails))
        args = argparse.Namespace(scene=self.scene, ritr=self.ritr, quick=quick, reuse=reuse, timing_repeats=repeats)
        with open(self.scene) as f:
            return run_rung(args, f.read(), "ritr", {}, self.work.name)

    def calls(self):
        with open(os.path.join(self.work.name, "calls")) as f:
            return int(f.read())

    def summary_time(self):
        with open(os.path.join(self.work.name, "ritr", "summary.json")) as f:
            return json.load(f)["total_wall_seconds"]

    def test_a_short_run_keeps_its_fastest_time(self):
        run = self.run_it([0.9, 0.5, 0.7])
        self.assertEqual(self.calls(), 3)
        self.assertEqual(run["total_wall_seconds"], 0.5)
        self.assertEqual(run["timing_repeats"], 3)
        # The repeats ran elsewhere: the run's own outputs are the first run's, the scratch is gone.
        self.assertEqual(self.summary_time(), 0.9)
        self.assertFalse(os.path.exists(os.path.join(self.work.name, "ritr.repeat")))
        with open(os.path.join(self.work.name, "ritr.measured.json")) as f:
            self.assertEqual(json.load(f)["fastest_own_seconds"], 0.5)
        # A ladder that reuses it keeps the fastest time, though summary.json holds the last.
        again = self.run_it([0.9, 0.5, 0.7], reuse=True)
        self.assertEqual(self.calls(), 3)
        self.assertEqual(again["total_wall_seconds"], 0.5)

    def test_a_reused_run_timed_once_gets_the_repeats_it_lacks(self):
        self.run_it([0.9, 0.5, 0.7], repeats=1)
        self.assertEqual(self.calls(), 1)
        run = self.run_it([0.9, 0.5, 0.7], reuse=True)
        self.assertEqual(self.calls(), 3)
        self.assertEqual(run["total_wall_seconds"], 0.5)
        self.assertEqual(run["timing_repeats"], 3)
        self.assertEqual(self.summary_time(), 0.9)

    def test_a_failed_repeat_stops_the_repeats_and_keeps_the_run(self):
        run = self.run_it([0.9, 0.5, 0.7], fails=[1])
        self.assertEqual(self.calls(), 2)
        self.assertEqual(run["exit_code"], 0)
        self.assertEqual(run["total_wall_seconds"], 0.9)
        self.assertEqual(run["timing_repeats"], 1)
        self.assertIn("exit 1", run["timing_repeat_failure"])
        self.assertEqual(self.summary_time(), 0.9)

    def test_a_quick_run_runs_once(self):
        run = self.run_it([0.9, 0.5, 0.7], quick=True)
        self.assertEqual(self.calls(), 1)
        self.assertNotIn("timing_repeats", run)

    def test_a_failed_run_is_not_repeated(self):
        run = self.run_it([0.9, 0.5, 0.7], fails=[0])
        self.assertEqual(self.calls(), 1)
        self.assertEqual(run["exit_code"], 1)
        self.assertNotIn("timing_repeats", run)

    def test_a_long_run_runs_once(self):
        run = self.run_it([25.0, 1.0, 1.0])
        self.assertEqual(self.calls(), 1)
        self.assertEqual(run["total_wall_seconds"], 25.0)
        self.assertNotIn("timing_repeats", run)


if __name__ == "__main__":
    unittest.main()
