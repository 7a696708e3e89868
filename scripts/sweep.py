#!/usr/bin/python3
"""Time to accuracy of r-ITR's settings: a grid of r-ITR runs against a fixed-mesh ladder.

    scripts/sweep.py SCENE.prm --fixed 0 1 2 --reference 3
        --vary "Adaptivity/hessian=reduced,quasi-newton" --vary "Adaptivity/max iterations=1,2,4"
        [--set PATH=VALUE ...] [--accuracy-until T] [--work DIR] [--timing-repeats N] [--reuse] [--quick] [--out RESULT.json]

The fixed rungs are the scene without adaptivity refined k more times (scripts/ladder.py);
the reference is one more, finer rung that every other run is measured against (mean over
frames of the Hausdorff distance between deformed boundaries, `ritr-compare`; with
`--accuracy-until T` over the frames up to time T only, where the reference is converged, as in
scripts/ladder.py). The r-ITR runs
are the scene on its own mesh with every combination of the `--vary` values (each
PATH=V1,V2,...), `--set` applying to all runs. A run's time is its own wall time from
summary.json (set-up, steps and output; not the program's start-up, the same for every run).
The result holds every run with its time over that of a fixed mesh of its accuracy
(interpolated between the rungs), the front of all of them and r-ITR's own front, its knee
(scripts/accuracy_front.py), the run of the best time to accuracy (the smallest such ratio),
and the verdicts of both against the fixed rungs; the runs go
one after another, so that their times are comparable; `--timing-repeats N` times each run
shorter than ten seconds as the fastest of N. `--reuse` keeps runs already finished
in the work directory with the same input and resumes stopped ones (a sweep cut short goes on
where it stopped; scripts/ladder.py). `--quick` runs two steps of
the two coarsest fixed rungs (the second as the reference) and of the first two r-ITR
settings, so that the sweep cannot rot unnoticed. The exit code is 1 if a run failed or broke
an invariant (the JSON is written first).
"""
import argparse
import itertools
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from accuracy_front import front, knee, verdict  # noqa: E402
from ladder import compare, failed_runs, run_rung, rung_overrides, scene_name, write_result  # noqa: E402


def variants(vary):
    """Every combination of the --vary values: a list of {path: value}."""
    axes = []
    for item in vary:
        path, values = item.split("=", 1)
        axes.append([(path, v.strip()) for v in values.split(",")])
    return [dict(combination) for combination in itertools.product(*axes)]


def variant_name(settings):
    short = {"Adaptivity/": "", "hessian": "", "max iterations": "it", "epsilon r": "eps",
             "trial iterations": "trial", "inner tolerance factor": "tol", " ": "_", "/": "_"}
    name = "ritr"
    for path, value in settings.items():
        key = path
        for long, brief in short.items():
            key = key.replace(long, brief)
        name += f"_{key}{value}"
    return name


def run(args, scene_text, name, overrides, work, reference=None):
    result = run_rung(args, scene_text, name, overrides, work)  # with --reuse, a finished run is kept
    result["seconds"] = result.get("total_wall_seconds", result["wall_seconds"])
    if reference is not None:
        compare(args, result, reference, until=args.accuracy_until)
    return result


def main():
    build = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build")
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("scene")
    p.add_argument("--fixed", type=int, nargs="+", required=True, help="refinements of the fixed rungs")
    p.add_argument("--reference", type=int, required=True, help="refinements of the reference rung")
    p.add_argument("--vary", action="append", default=[], metavar="PATH=V1,V2",
                   help="an r-ITR setting and its values; the runs take every combination")
    p.add_argument("--set", action="append", default=[], metavar="PATH=VALUE", help="override for every run")
    p.add_argument("--accuracy-until", type=float, metavar="T",
                   help="accuracy over the frames up to time T only (where the reference is converged)")
    p.add_argument("--work", help="directory for the runs (default: a temporary one)")
    p.add_argument("--timing-repeats", type=int, default=1, metavar="N",
                   help="time each run shorter than ten seconds as the fastest of N runs (scripts/ladder.py)")
    p.add_argument("--reuse", action="store_true",
                   help="keep the runs of the work directory that finished with the same input (scripts/ladder.py)")
    p.add_argument("--quick", action="store_true", help="two steps of the coarsest runs only")
    p.add_argument("--out", help="result JSON (default: stdout)")
    p.add_argument("--ritr", default=os.path.join(build, "ritr"))
    p.add_argument("--compare", default=os.path.join(build, "ritr-compare"))
    args = p.parse_args()

    with open(args.scene) as f:
        scene_text = f.read()
    for setting in args.set + args.vary:
        if "=" not in setting:
            p.error(f"'{setting}' is not PATH=VALUE")
    common = dict(item.split("=", 1) for item in args.set)
    work = args.work or tempfile.mkdtemp(prefix="sweep-")
    os.makedirs(work, exist_ok=True)

    def fixed(k, reference=None):
        return dict(run(args, scene_text, f"fixed_r{k}", {**common, **rung_overrides(scene_text, k, False)},
                        work, reference), refinements=k, adaptivity=False)

    fixed_rungs = sorted(set(args.fixed) - {args.reference})
    if args.quick:  # scripts/ladder.py's run_rung runs two steps of each
        args.reference, fixed_rungs = sorted(set(args.fixed) | {args.reference})[1], fixed_rungs[:1]
    reference = fixed(args.reference)
    rungs = [fixed(k, reference) for k in fixed_rungs]
    ritr_runs = []
    for settings in variants(args.vary)[:2 if args.quick else None]:
        overrides = {**common, **rung_overrides(scene_text, 0, True), **settings}
        ritr_runs.append(dict(run(args, scene_text, variant_name(settings), overrides, work, reference),
                              settings=settings, adaptivity=True))

    measured = [r for r in rungs + ritr_runs if r["exit_code"] == 0 and "mean_hausdorff" in r]
    measured_ritr = [r for r in measured if r["adaptivity"]]
    measured_fixed = [r for r in measured if not r["adaptivity"]]
    for r in measured_ritr:
        r["time_to_accuracy"] = verdict(r, measured_fixed) if measured_fixed else None
    chosen = knee(measured_ritr)
    ratios = [r for r in measured_ritr if (r["time_to_accuracy"] or {}).get("interpolated_ratio")]
    best = min(ratios, key=lambda r: r["time_to_accuracy"]["interpolated_ratio"]) if ratios else None
    result = {"scene": scene_name(args.scene), "overrides": common, "vary": args.vary, "reference": reference["name"],
              "accuracy_until": args.accuracy_until,
              "runs": [reference] + rungs + ritr_runs,
              "front": [r["name"] for r in front(measured)],
              "ritr_front": [r["name"] for r in front(measured_ritr)],
              "knee": chosen["name"] if chosen else None,
              "knee_verdict": verdict(chosen, measured_fixed) if chosen and measured_fixed else None,
              "best": best["name"] if best else None,
              "best_verdict": best["time_to_accuracy"] if best else None}
    for r in result["runs"]:
        r.pop("directory", None)
    write_result(result, args.out)
    if result["knee_verdict"]:
        print(f"sweep: knee {chosen['name']}: {result['knee_verdict']['sentence']}", file=sys.stderr)
    if best:
        print(f"sweep: best time to accuracy {best['name']}: {result['best_verdict']['sentence']}", file=sys.stderr)
    failed = failed_runs(result["runs"])
    if failed:
        print("sweep: failed or broke an invariant: " + ", ".join(failed), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
