#!/usr/bin/python3
"""Varying friction (paper Fig. 21): r-ITR and fixed meshes over friction coefficients.

    scripts/friction_sweep.py SCENE.prm --mu 0 0.1 0.5 --fixed 0 1 2 3 --pass-below -0.4
        [--expect pass pass caught] [--expect-fixed caught caught caught] [--quick] [--out RESULT.json]

For every coefficient (`Contact/friction coefficient`) r-ITR and the fixed mesh of the same
size run the scene; the fixed refinement ladder (rung k: every body refined k more times) runs
at the first coefficient. Each run is its own process, timed from outside as in
scripts/ladder.py. A run passes when the area centroid of its bodies ends below the height
`--pass-below`, and is caught otherwise; the centroid's height over time is kept for the plot
(scripts/friction_sweep_report.py). The headline: the coarsest fixed rung that passes at the
first coefficient, and r-ITR's time and memory ratios to it.

The exit code is 1 if a run failed or broke an invariant, if the outcomes differ from
`--expect` (r-ITR, one per coefficient) or `--expect-fixed` (the fixed mesh of r-ITR's size),
or if r-ITR's final centroids do not fall as friction falls (the JSON is written first).
`--quick` runs two steps of every run and of the two coarsest rungs and checks no outcome.
"""
import argparse
import os
import sys
import tempfile
from types import SimpleNamespace

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from frame_metrics import centroid_heights  # noqa: E402
from ladder import cost_ratios, failed_runs, measure, run_rung, rung_overrides, scene_name, write_result  # noqa: E402


def outcome(run):
    return "pass" if run["passes"] else "caught"


def check(args, runs):
    """The failures of the expected outcomes, as lines."""
    ritr = [r for r in runs if r["adaptivity"]]
    same_size = [r for r in runs if not r["adaptivity"] and r["refinements"] == 0]
    problems = []
    for expected, group, label in ((args.expect, ritr, "r-ITR"), (args.expect_fixed, same_size, "fixed")):
        for want, run in zip(expected or [], group):
            if outcome(run) != want:
                problems.append(f"{label} at mu {run['mu']:g}: {outcome(run)} (centroid {run['final_centroid']:.3f}), "
                                f"expected {want}")
    # Lower friction slides through faster: r-ITR's final centroid falls as mu falls.
    by_mu = sorted(ritr, key=lambda r: r["mu"])
    for lower, higher in zip(by_mu, by_mu[1:]):
        if not lower["final_centroid"] < higher["final_centroid"]:
            problems.append(f"r-ITR ends higher at mu {lower['mu']:g} ({lower['final_centroid']:.3f}) than at mu "
                            f"{higher['mu']:g} ({higher['final_centroid']:.3f})")
    return problems


def headline(runs, baseline_rss):
    ritr = runs[0]
    ladder = sorted((r for r in runs if not r["adaptivity"] and r["mu"] == ritr["mu"] and r["exit_code"] == 0),
                    key=lambda r: r["refinements"])
    passing = next((r for r in ladder if r["passes"]), None)
    if ritr["exit_code"] != 0:
        return {"matching_fixed": None, "why": "r-ITR did not finish"}
    if passing is None:
        return {"matching_fixed": None, "why": f"no fixed rung passes at mu {ritr['mu']:g}"}
    return dict(cost_ratios(ritr, passing, baseline_rss),
                why=f"coarsest fixed rung that passes at mu {ritr['mu']:g}; r-ITR "
                    + ("passes" if ritr["passes"] else "is caught"))


def main():
    build = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build")
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("scene")
    p.add_argument("--mu", type=float, nargs="+", required=True, help="friction coefficients")
    p.add_argument("--fixed", type=int, nargs="+", required=True, help="refinements of the fixed rungs")
    p.add_argument("--pass-below", type=float, required=True, metavar="Y",
                   help="a run passes when the bodies' area centroid ends below height Y")
    p.add_argument("--expect", choices=("pass", "caught"), nargs="+", help="r-ITR's outcome per coefficient")
    p.add_argument("--expect-fixed", choices=("pass", "caught"), nargs="+",
                   help="the outcome per coefficient of the fixed mesh of r-ITR's size")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--out", help="result JSON (default: stdout)")
    p.add_argument("--work", help="directory for the runs (default: a temporary one)")
    p.add_argument("--ritr", default=os.path.join(build, "ritr"))
    args = p.parse_args()

    with open(args.scene) as f:
        scene_text = f.read()
    work = args.work or tempfile.mkdtemp(prefix="friction-sweep-")
    os.makedirs(work, exist_ok=True)
    _, _, baseline_rss = measure([args.ritr, "--help"], os.path.join(work, "baseline.log"))
    ladder_args = SimpleNamespace(scene=args.scene, quick=args.quick, ritr=args.ritr, reuse=False)

    def run(name, mu, k, adaptivity):
        overrides = dict(rung_overrides(scene_text, k, adaptivity), **{"Contact/friction coefficient": repr(mu)})
        r = dict(run_rung(ladder_args, scene_text, name, overrides, work), mu=mu, refinements=k, adaptivity=adaptivity)
        if r["exit_code"] == 0:
            r["centroid_over_time"] = centroid_heights(r["directory"])
            r["final_centroid"] = r["centroid_over_time"][-1][1]
            r["passes"] = r["final_centroid"] < args.pass_below
        return r

    rungs = sorted(args.fixed)[:2] if args.quick else sorted(args.fixed)
    runs = [run(f"ritr_mu{mu:g}", mu, 0, True) for mu in args.mu]
    runs += [run(f"fixed_r0_mu{mu:g}", mu, 0, False) for mu in args.mu]
    runs += [run(f"fixed_r{k}_mu{args.mu[0]:g}", args.mu[0], k, False) for k in rungs if k != 0]
    for r in runs:
        r.pop("directory")

    failed = failed_runs(runs)
    problems = [] if args.quick or failed else check(args, runs)
    result = {"scene": scene_name(args.scene), "quick": args.quick, "pass_below": args.pass_below,
              "mu": args.mu, "baseline_rss_bytes": baseline_rss, "runs": runs,
              "headline": headline(runs, baseline_rss), "unexpected": problems}
    write_result(result, args.out)
    for r in runs:
        if "passes" in r:
            status = "quick run" if args.quick else outcome(r)
            print(f"friction_sweep: {r['name']}: {status} (centroid {r['final_centroid']:.3f}), "
                  f"{r['wall_seconds']:.1f} s", flush=True)
    if failed:
        print("friction_sweep: failed or broke an invariant: " + ", ".join(failed), file=sys.stderr)
        return 1
    for line in problems:
        print("friction_sweep: " + line, file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
