#!/usr/bin/python3
"""scripts/benchmark_report.py on copies of doc/benchmarks: a missing result becomes a note, a
sweep's table is sweep_report.table()'s, a changed figure fails --check naming its scene, a
claim of the prose that a result no longer bears out fails, and the scenes' headings give the
anchors the README links."""
import contextlib
import io
import json
import math
import os
import shutil
import sys
import tempfile
import unittest

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import benchmark_report  # noqa: E402
import sweep_report  # noqa: E402

RESULTS = os.path.join(ROOT, "doc", "benchmarks")
ANCHORS = ["deep-punch", "deep-punch-036", "static-drop-through", "stamping", "bending-beam", "ball-on-spikes",
           "bar-impact", "masticator", "varying-friction", "drop-through-3d"]


class BenchmarkReport(unittest.TestCase):
    def setUp(self):
        self.work = tempfile.mkdtemp(prefix="benchmark-report-")
        self.results = os.path.join(self.work, "benchmarks")
        shutil.copytree(RESULTS, self.results)
        for name in ("ball_on_spikes_sweep", "bar_impact_sweep"):
            for suffix in (".json", "_pareto.png"):
                path = os.path.join(self.results, name + suffix)
                if os.path.exists(path):
                    os.remove(path)
        self.out = os.path.join(self.work, "benchmarks.md")

    def tearDown(self):
        shutil.rmtree(self.work)

    def run_script(self, *options):
        """(exit code, stderr) of the script on the copies."""
        stderr = io.StringIO()
        with contextlib.redirect_stderr(stderr):
            code = benchmark_report.main(["--results", self.results, "--out", self.out, *options])
        return code, stderr.getvalue()

    def text(self):
        with open(self.out) as f:
            return f.read()

    def edit(self, name, change):
        path = os.path.join(self.results, name + ".json")
        with open(path) as f:
            result = json.load(f)
        change(result)
        with open(path, "w") as f:
            json.dump(result, f)

    def test_written_document_passes_its_check(self):
        self.assertEqual(self.run_script(), (0, ""))
        self.assertEqual(self.run_script("--check"), (0, ""))

    def test_missing_result_becomes_a_note(self):
        self.run_script()
        text = self.text()
        self.assertIn("Not measured yet: `doc/benchmarks/ball_on_spikes_sweep.json` is missing", text)
        self.assertIn("`ctest -R '^paper_bar_impact_sweep$'`", text)

    def test_sweep_is_rendered_with_its_table_and_plot(self):
        shutil.copy(os.path.join(RESULTS, "ball_on_spikes_sweep.json"), self.results)
        with open(os.path.join(self.results, "ball_on_spikes_sweep.json")) as f:
            result = json.load(f)
        self.assertEqual(self.run_script(), (0, ""))
        text = self.text()
        self.assertIn(sweep_report.table(result), text)
        self.assertIn("](benchmarks/ball_on_spikes_sweep_pareto.png)", text)
        self.assertTrue(os.path.exists(os.path.join(self.results, "ball_on_spikes_sweep_pareto.png")))
        self.assertNotIn("ball_on_spikes_sweep.json` is missing", text)

    def test_a_changed_figure_fails_the_check_naming_its_scene(self):
        self.run_script()

        def change(result):
            result["runs"][0]["mean_hausdorff"] *= 1.01
        self.edit("bar_impact", change)
        code, message = self.run_script("--check")
        self.assertEqual(code, 1)
        self.assertEqual(len(message.strip().splitlines()), 1)
        self.assertIn("section bar_impact", message)

    def test_an_edited_document_fails_the_check(self):
        self.run_script()
        with open(self.out) as f:
            text = f.read()
        with open(self.out, "w") as f:
            f.write(text.replace("| fixed_r2 | 4,753 |", "| fixed_r2 | 4,754 |", 1))
        code, message = self.run_script("--check")
        self.assertEqual(code, 1)
        self.assertIn("section deep_punch ", message)

    def test_a_claim_the_results_no_longer_bear_out_fails(self):
        def change(result):
            result["runs"][0]["final_energy"] = 1e9
        self.edit("deep_punch", change)
        code, message = self.run_script()
        self.assertEqual(code, 1)
        self.assertIn("deep_punch (doc/benchmarks/deep_punch.json): the prose's claim `ritr.E < finest.E`", message)

    def test_a_figure_of_a_missing_run_names_the_scene(self):
        def change(result):
            result["runs"] = [r for r in result["runs"] if r["name"] != "ritr_held_base"]
        self.edit("deep_punch", change)
        code, message = self.run_script()
        self.assertEqual(code, 1)
        self.assertIn("deep_punch (doc/benchmarks/deep_punch.json)", message)
        self.assertIn("no run ritr_held_base", message)

    def test_headings_give_the_readmes_anchors(self):
        self.run_script()
        slugs = [benchmark_report.slug(line) for line in self.text().splitlines() if line.startswith("#")]
        for anchor in ANCHORS:
            self.assertEqual(slugs.count(anchor), 1, anchor)
        self.assertEqual(benchmark_report.slug("### Deep punch, 0.36"), "deep-punch-036")
        self.assertEqual(benchmark_report.slug("### Drop-through, 3D"), "drop-through-3d")

    def test_placeholders_and_formats(self):
        with open(os.path.join(RESULTS, "deep_punch.json")) as f:
            result = json.load(f)
        names = benchmark_report.namespace("deep_punch", result)
        self.assertEqual(benchmark_report.fill("{{ritr.v}} and {{finest.E|.1f}}", names, "test"),
                         f"{names['ritr'].v:,} and {names['finest'].E:.1f}")
        self.assertEqual(benchmark_report.fmt(1.64, "%"), "1.6")
        self.assertEqual(benchmark_report.fmt(28.3, "%"), "28")
        self.assertEqual(benchmark_report.fmt(0.021, "%"), "0.02")
        self.assertEqual(names["rel"](1.0, 2.5, "lower", "higher"), "2.5x lower")
        self.assertEqual(names["rel"](1.1, 1.0, "lower", "higher"), "10 % higher")
        with self.assertRaises(benchmark_report.ReportError):
            benchmark_report.fill("{{run('nothing').E}}", names, "test")

    def test_end_heights(self):
        # ladder.py --end-heights: [time, left, right] per frame; an end is under the bar below -0.5.
        with open(os.path.join(RESULTS, "deep_punch.json")) as f:
            result = json.load(f)
        result["runs"][0]["end_heights_over_time"] = [[0.0, 0.1, 0.2], [0.5, -0.6, 0.1], [1.0, -1.0, -0.7]]
        names = benchmark_report.namespace("deep_punch", result)
        ritr = names["ritr"]
        self.assertEqual(names["end_drop"](ritr, 0), 0.5)
        self.assertEqual(names["end_drop"](ritr, 1), 1.0)
        self.assertEqual(names["end_drop"](ritr, 1, 0.15), 0.5)
        self.assertTrue(math.isnan(names["end_drop"](names["finest"], 0)))  # no heights recorded
        self.assertEqual([r.name for r in names["runs_like"]("fixed_")], [r.name for r in names["fixed"]])
        self.assertEqual(names["runs_like"]("no such run"), [])
        self.assertEqual(names["mean"]([1.0, 2.0, 6.0]), 3.0)
        self.assertTrue(math.isnan(names["mean"]([])))
        table = names["end_table"]([ritr.name], [0.5, 2.0]).splitlines()
        self.assertEqual(table[2], f"| {ritr.name} | {ritr.v:,} | -0.60 / +0.10 | - |")


if __name__ == "__main__":
    unittest.main()
