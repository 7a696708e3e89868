#!/usr/bin/python3
"""The results table of the README: one row per paper scene, r-ITR against its fixed ladder,
read from the ladders' results (doc/benchmarks/NAME.json, scripts/ladder.py and
scripts/friction_sweep.py).

    scripts/results_table.py             print the table (Markdown)
    scripts/results_table.py --update    write it into README.md between its markers
    scripts/results_table.py --check     exit 1 if README.md's table is not the one printed

Times are the runs' own wall times (summary.json: set-up, steps and output, not the program's
start-up), all of one ladder taken one after another on one machine.
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchmark_report import percent, seconds_text  # noqa: E402
from ladder import further_than_every_rung, run_seconds  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
BEGIN, END = "<!-- results table: scripts/results_table.py -->", "<!-- end of results table -->"

# (JSON name, what the scene is), in the order of the table.
SCENES = [
    ("deep_punch", "Deep punch, statics (Fig. 16)"),
    ("deep_punch_036", "Deep punch to 0.36 (Fig. 16)"),
    ("static_drop_through", "Static drop-through (Fig. 18)"),
    ("stamping", "Stamping, 2D sections (Fig. 23)"),
    ("stamping_3d", "Stamping, 3D (Fig. 23)"),
    ("bending_beam", "Bending beam, statics (Fig. 20)"),
    ("ball_on_spikes", "Ball on spikes, dynamics (Fig. 6)"),
    ("bar_impact", "Bar impact at 80 m/s (Fig. 13)"),
    ("masticator", "Masticator (Figs 3, 4)"),
    ("varying_friction", "Wedge through a gap, mu 0 (Fig. 21)"),
    ("drop_through_3d", "3D drop-through (Fig. 2)"),
    ("chicken_drop", "Chicken drop, 3D (Fig. 10)"),
    ("jelly_poke", "Jelly poke, 3D (Fig. 1)"),
]


def duration(run):
    return f"{seconds_text(run_seconds(run))} s"


def vertices(run):
    return f"{run.get('n_vertices', 0):,}"


def row(name, title):
    with open(os.path.join(ROOT, "doc", "benchmarks", name + ".json")) as f:
        result = json.load(f)
    runs = {r["name"]: r for r in result["runs"]}
    head = result["headline"]
    ritr = runs.get("ritr") or runs.get("ritr_mu0")
    fixed = runs.get(head.get("matching_fixed") or "")
    link = f"[{title}](doc/benchmarks.md#{name.replace('_', '-')})"
    ritr_measure = None  # r-ITR's figure where it is not measure(ritr)
    if result.get("accuracy") == "energy":
        measure = lambda r: f"energy {r['final_energy']:.6g}"
        if fixed is None:
            return f"| {link} | {vertices(ritr)} | {measure(ritr)} | {duration(ritr)} | - | - | - | {head['why']} |"
        lower = ritr["final_energy"] < fixed["final_energy"]
        verdict = (f"lower energy than the {vertices(fixed)}-vertex mesh in {percent(100 * run_seconds(ritr) / run_seconds(fixed))} % "
                   f"of its time" if lower else
                   f"the {vertices(fixed)}-vertex mesh is lower, in {percent(100 * run_seconds(fixed) / run_seconds(ritr))} % of r-ITR's time")
    elif "passes" in ritr or "centroid_over_time" in ritr or name == "varying_friction":
        passing = lambda r: "passes" if r.get("passes") else "locks"
        measure = lambda r: passing(r)
        if fixed is None:
            finest = max((r for r in result["runs"] if not r.get("adaptivity", r["name"].startswith("ritr"))),
                         key=lambda r: r.get("n_vertices", 0))
            return (f"| {link} | {vertices(ritr)} | {measure(ritr)} | {duration(ritr)} | {vertices(finest)} "
                    f"| {measure(finest)} | {duration(finest)} | no fixed rung passes |")
        verdict = f"passes like the {vertices(fixed)}-vertex mesh in {percent(100 * run_seconds(ritr) / run_seconds(fixed))} % of its time"
        if further_than_every_rung(head):
            verdict += "; by distance to it, further than every coarser rung"
    else:
        until = result.get("accuracy_until")
        window = f" (t <= {until:g})" if until is not None else ""
        measure = lambda r: f"Hausdorff {r['mean_hausdorff']:.2g}{window}" if "mean_hausdorff" in r else "reference"
        if head.get("draws"):
            # Judged over draws (scripts/ladder.py --draws): the mean of the scene's run and its
            # perturbed repeats, at the scene's run's time.
            of_draws = f"Hausdorff {head['ritr_mean_hausdorff']:.2g}{window}, mean of {len(head['draws'])} runs"
            ritr_measure = lambda r: of_draws
        ratio = (head.get("time_to_accuracy") or {}).get("interpolated_ratio")
        verdict = (f"a fixed mesh as accurate (between the rungs) takes {1 / ratio:.1f}x r-ITR's time"
                   if ratio else head.get("why", ""))
    ritr_measure = ritr_measure or measure
    if fixed is None:
        return f"| {link} | {vertices(ritr)} | {ritr_measure(ritr)} | {duration(ritr)} | - | - | - | {verdict} |"
    return (f"| {link} | {vertices(ritr)} | {ritr_measure(ritr)} | {duration(ritr)} | {vertices(fixed)} | "
            f"{measure(fixed)} | {duration(fixed)} | {verdict} |")


def table():
    lines = ["| scene | r-ITR vertices | r-ITR | time | fixed vertices | fixed | time | r-ITR against the fixed ladder |",
             "| --- | --- | --- | --- | --- | --- | --- | --- |"]
    lines += [row(name, title) for name, title in SCENES if os.path.exists(os.path.join(ROOT, "doc", "benchmarks", name + ".json"))]
    return "\n".join(lines)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--update", action="store_true")
    p.add_argument("--check", action="store_true")
    args = p.parse_args()
    text = table()
    if not (args.update or args.check):
        print(text)
        return 0
    path = os.path.join(ROOT, "README.md")
    with open(path) as f:
        readme = f.read()
    if BEGIN not in readme or END not in readme:
        print(f"results_table: {path} has no {BEGIN} ... {END}", file=sys.stderr)
        return 1
    start, stop = readme.index(BEGIN) + len(BEGIN), readme.index(END)
    if args.check:
        if readme[start:stop].strip() != text:
            print("results_table: README.md's table differs from doc/benchmarks/*.json "
                  "(scripts/results_table.py --update)", file=sys.stderr)
            return 1
        return 0
    with open(path, "w") as f:
        f.write(readme[:start] + "\n" + text + "\n" + readme[stop:])
    return 0


if __name__ == "__main__":
    sys.exit(main())
