#!/usr/bin/python3
"""The r-ITR outer solve, compared across outer Hessians and tolerances on one scene.

    scripts/outer_solve.py SCENE.prm --ritr build/ritr [--hessian truncated reduced/exact ...]
                           [--epsilon 1e-4 1e-6] [--end-time T] [--work DIR]

A variant is an outer Hessian, optionally with the transfer's integration after a slash
(reduced/quadrature, reduced/exact; without one, the scene's). For every (epsilon r, variant)
pair the scene runs once, in turn, in its own process; at epsilon r below 1e-5 the outer
iteration limit is raised to 200. From each log.csv: why each step's outer iteration ended
(the outer_stop column), the mean outer iterations, the inner Newton iterations and trials,
the total decrease of R over the steps (sum of initial_objective - energy), the wall time of
the steps and the time of an r-ITR step over a step of the same scene on its fixed mesh (run
first); "idle/fixed" is the same ratio for the steps whose outer solve stopped at its first
check (no mesh moved), the floor of an r-ITR step; "inner/fixed" is the time of an r-ITR step's inner solves alone (the start-of-step solve
and every trial's) over a fixed step, a floor that no cheaper outer model can lower, and
"newton/fixed" the same for inner Newton iterations (which do not depend on the machine's
speed). Later steps of different runs start from different states, so the decrease of R is a
sum of per-step gains, comparable between the runs of one table. Ratios are taken within one
epsilon r against the first variant named. The exit code is 1 if a run failed, or with
--require-converging VARIANT if a run of VARIANT at epsilon r below 1e-5 left a step on the
iteration limit or took more than 15 outer iterations per step on average.
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from prm_variant import write_variant  # noqa: E402


# A converging outer solve at a tight epsilon r takes at most this many outer iterations per
# step on average.
MAX_MEAN_OUTER = 15


def summarize(log_csv):
    rows = list(csv.DictReader(open(log_csv)))
    outer = [int(r["outer_iterations"]) for r in rows]
    stops = [r["outer_stop"] for r in rows]
    return {
        "steps": len(rows),
        "converged": stops.count("converged"),
        "small_decrease": stops.count("small_decrease"),
        "no_decrease": stops.count("no_decrease"),
        "at_limit": stops.count("iteration_limit"),
        "mean_outer": sum(outer) / max(len(rows), 1),
        "inner": sum(int(r["inner_newton_iterations"]) for r in rows),
        "trials": sum(int(r["line_search_trials"]) for r in rows),
        "decrease": sum(float(r["initial_objective"]) - float(r["energy"]) for r in rows),
        "wall": sum(float(r["wall_seconds"]) for r in rows),
        "inner_seconds": sum(float(r["inner_solve_seconds"]) for r in rows),
        # Steps whose outer solve stopped at its first check: what deciding costs when no
        # mesh moves (the start-of-step solve, one evaluation of R's derivatives, S).
        "idle_walls": [float(r["wall_seconds"]) for r, n in zip(rows, outer) if n == 0],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene")
    parser.add_argument("--ritr", required=True)
    parser.add_argument("--hessian", nargs="+", default=["truncated", "reduced"])
    parser.add_argument("--epsilon", nargs="+", default=["1e-4", "1e-6"])
    parser.add_argument("--end-time")
    parser.add_argument("--work", default=None)
    parser.add_argument("--require-converging", metavar="VARIANT",
                        help="exit 1 if a run of VARIANT at epsilon r below 1e-5 leaves a step on the iteration "
                             f"limit or takes more than {MAX_MEAN_OUTER} outer iterations per step")
    args = parser.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="outer_solve_")
    os.makedirs(work, exist_ok=True)
    failed = False
    # The same scene on its fixed mesh: the cost every r-ITR step is compared with.
    fixed_prm = os.path.join(work, "fixed.prm")
    fixed_overrides = {"output directory": os.path.join(work, "fixed"), "output every": "1000000",
                       "Adaptivity/enabled": "false"}
    if args.end_time:
        fixed_overrides["end time"] = args.end_time
    write_variant(args.scene, fixed_overrides, fixed_prm)
    with open(os.path.join(work, "fixed.out"), "w") as log:
        if subprocess.call([args.ritr, fixed_prm], stdout=log, stderr=subprocess.STDOUT) != 0:
            print("the fixed-mesh run failed")
            return 1
    fixed = summarize(os.path.join(work, "fixed", "log.csv"))
    fixed_step = fixed["wall"] / max(fixed["steps"], 1)
    fixed_newton = fixed["inner"] / max(fixed["steps"], 1)
    print(f"fixed mesh: {fixed['steps']} steps, {fixed_step:.4f} s and {fixed_newton:.1f} Newton iterations per step")
    print(f"{'epsilon r':>9} {'variant':>18} {'steps':>5} {'converged':>9} {'small dec.':>10} {'no decr.':>8} {'at limit':>8} "
          f"{'outer/step':>10} {'inner':>7} "
          f"{'trials':>6} {'R decrease':>11} {'wall s':>8} {'step/fixed':>10} {'idle/fixed':>10} {'inner/fixed':>11} "
          f"{'newton/fixed':>12} "
          f"{'wall ratio':>10} "
          f"{'decrease ratio':>14}")
    for epsilon in args.epsilon:
        base = None
        for variant in args.hessian:
            hessian, _, integration = variant.partition("/")
            name = f"{variant.replace('/', '_')}_{epsilon}"
            limit = 200 if float(epsilon) < 1e-5 else None
            overrides = {"output directory": os.path.join(work, name), "output every": "1000000",
                         "Adaptivity/enabled": "true", "Adaptivity/hessian": hessian,
                         "Adaptivity/epsilon r": epsilon}
            if integration:
                overrides["Adaptivity/transfer integration"] = integration
            if limit:
                overrides["Adaptivity/max iterations"] = str(limit)
            if args.end_time:
                overrides["end time"] = args.end_time
            prm = os.path.join(work, name + ".prm")
            write_variant(args.scene, overrides, prm)
            with open(os.path.join(work, name + ".out"), "w") as log:
                code = subprocess.call([args.ritr, prm], stdout=log, stderr=subprocess.STDOUT)
            if code != 0:
                failed = True
                print(f"{epsilon:>9} {variant:>18} failed with exit code {code}")
                continue
            s = summarize(os.path.join(work, name, "log.csv"))
            not_converging = (variant == args.require_converging and limit and
                              (s["at_limit"] > 0 or s["mean_outer"] > MAX_MEAN_OUTER))
            base = base or s
            idle = (f"{sum(s['idle_walls']) / len(s['idle_walls']) / fixed_step:>10.1f}" if s["idle_walls"]
                    else f"{'-':>10}")
            print(f"{epsilon:>9} {variant:>18} {s['steps']:>5} {s['converged']:>9} {s['small_decrease']:>10} {s['no_decrease']:>8} "
                  f"{s['at_limit']:>8} {s['mean_outer']:>10.1f} "
                  f"{s['inner']:>7} {s['trials']:>6} {s['decrease']:>11.3e} {s['wall']:>8.1f} "
                  f"{s['wall'] / s['steps'] / fixed_step:>10.1f} {idle} "
                  f"{s['inner_seconds'] / s['steps'] / fixed_step:>11.1f} "
                  f"{s['inner'] / s['steps'] / fixed_newton:>12.1f} "
                  f"{s['wall'] / base['wall']:>10.2f} {s['decrease'] / base['decrease']:>14.2f}", flush=True)
            if not_converging:
                failed = True
                print(f"{epsilon:>9} {variant:>18} does not converge: {s['at_limit']} steps on the limit, "
                      f"{s['mean_outer']:.1f} outer iterations per step (at most {MAX_MEAN_OUTER})", flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
