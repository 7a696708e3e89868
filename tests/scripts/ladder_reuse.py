#!/usr/bin/python3
"""`ladder.py --reuse`: which runs an earlier ladder left in the work directory are taken as they
are (finished with the same entries, whatever the comments), resumed (stopped at a checkpoint) or run afresh
(scripts/ladder.py, earlier_run); and masticator_branches.py's restarts, which run afresh once the
frame they start from changed."""
import json
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
from ladder import earlier_run  # noqa: E402
from masticator_branches import frame_mesh_path  # noqa: E402

PRM = "set end time = 1\n"


class EarlierRun(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.TemporaryDirectory()
        self.directory = os.path.join(self.work.name, "fixed_r3")
        os.makedirs(self.directory)
        self.measured = os.path.join(self.work.name, "fixed_r3.measured.json")

    def tearDown(self):
        self.work.cleanup()

    def write(self, measured=None, summary=None, checkpoint=False):
        if measured is not None:
            with open(self.measured, "w") as f:
                json.dump(measured, f)
        if summary is not None:
            with open(os.path.join(self.directory, "summary.json"), "w") as f:
                json.dump(summary, f)
        if checkpoint:
            open(os.path.join(self.directory, "checkpoint.bin"), "wb").close()

    def finished(self, prm):
        """An earlier ladder's finished run of `prm`, and its measurement."""
        measurement = {"prm": prm, "exit_code": 0, "wall_seconds": 12.5, "peak_rss_bytes": 4096}
        self.write(measurement, {"complete": True}, checkpoint=True)
        return measurement

    def test_nothing_earlier_runs_afresh(self):
        self.assertIsNone(earlier_run(self.measured, PRM, self.directory))

    def test_finished_run_is_reused_with_its_measurement(self):
        measurement = self.finished(PRM)
        self.assertEqual(earlier_run(self.measured, PRM, self.directory), ("finished", measurement))

    def test_stopped_run_is_resumed(self):
        self.write({"prm": PRM}, {"complete": False}, checkpoint=True)
        self.assertEqual(earlier_run(self.measured, PRM, self.directory)[0], "stopped")

    def test_killed_before_its_summary_is_resumed(self):
        self.write({"prm": PRM}, checkpoint=True)
        self.assertEqual(earlier_run(self.measured, PRM, self.directory)[0], "stopped")

    def test_other_input_runs_afresh(self):
        self.write({"prm": PRM, "exit_code": 0, "wall_seconds": 1, "peak_rss_bytes": 1}, {"complete": True},
                   checkpoint=True)
        self.assertIsNone(earlier_run(self.measured, "set end time = 2\n", self.directory))

    def test_edited_comments_keep_a_finished_run(self):
        measurement = self.finished(PRM)
        commented = "# a scene whose comments were reworded\nset end time = 1   # seconds\n"
        self.assertEqual(earlier_run(self.measured, commented, self.directory), ("finished", measurement))

    def test_outer_solve_settings_keep_a_finished_fixed_run(self):
        fixed = "subsection Adaptivity\n  set enabled = false\n  set max iterations = 1\nend\n"
        measurement = self.finished(fixed)
        retuned = fixed.replace("max iterations = 1", "max iterations = 3")
        self.assertEqual(earlier_run(self.measured, retuned, self.directory), ("finished", measurement))
        adaptive = retuned.replace("enabled = false", "enabled = true")
        self.finished(fixed.replace("enabled = false", "enabled = true"))
        self.assertIsNone(earlier_run(self.measured, adaptive, self.directory))

    def test_work_directory_spelled_otherwise_keeps_a_finished_run(self):
        relative = "set output directory = build/paper/fixed_r3\nset end time = 1\n"
        measurement = self.finished(relative)
        absolute = relative.replace("build/paper", "/home/user/ritr/build/paper")
        self.assertEqual(earlier_run(self.measured, absolute, self.directory), ("finished", measurement))

    def test_run_stopped_on_the_newton_cap_resumes_with_a_larger_one(self):
        capped = PRM + "subsection Solver\n  set max iterations = 1000\nend\n"
        self.write({"prm": capped, "exit_code": 3, "wall_seconds": 1, "peak_rss_bytes": 1}, {"complete": False},
                   checkpoint=True)
        status, _ = earlier_run(self.measured, capped.replace("1000", "5000"), self.directory)
        self.assertEqual(status, "stopped")

    def test_failed_run_without_checkpoint_runs_afresh(self):
        self.write({"prm": PRM, "exit_code": 3, "wall_seconds": 1, "peak_rss_bytes": 1}, {"complete": False})
        self.assertIsNone(earlier_run(self.measured, PRM, self.directory))

    def test_restart_from_a_changed_frame_runs_afresh(self):
        # The restart's entries name the frame's mesh, which is named by the frame's content: the
        # same frame path with other content (its source run ran again) gives other entries.
        frame = os.path.join(self.work.name, "solution-00088.vtu")

        def restart_prm(content):
            with open(frame, "w") as f:
                f.write(content)
            mesh = frame_mesh_path(self.work.name, "ritr", frame)
            return f"set start from = {frame}\nsubsection Body 0\n  set file = {mesh}\nend\n"

        earlier = restart_prm("the old run's frame")
        self.finished(earlier)
        self.assertEqual(restart_prm("the old run's frame"), earlier)
        self.assertEqual(earlier_run(self.measured, earlier, self.directory)[0], "finished")
        self.assertIsNone(earlier_run(self.measured, restart_prm("the new run's frame"), self.directory))


if __name__ == "__main__":
    unittest.main()
