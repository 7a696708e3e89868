#!/usr/bin/python3
"""Accuracy for cost: an r-ITR run of a scene against a fixed-mesh refinement ladder.

    scripts/ladder.py SCENE.prm --fixed 0 1 2 3 [--quick] [--out RESULT.json]

SCENE.prm is the r-ITR run (its `Adaptivity/enabled` is forced on). Fixed rung k is the
same scene without adaptivity and with every body refined k more times (edge subdivision,
the paper's ladder); `--fixed-subdivide M` adds rungs between those with every body's
`subdivisions` multiplied by M. Each run is its own process; its wall time and peak resident
memory are taken from outside it (wait4), and so is the start-up baseline (`ritr --help`), which
memory ratios subtract; time ratios take the runs' own wall times from summary.json, which leave
out the program's start-up. Accuracy is the mean over frames of the Hausdorff distance between
deformed boundaries (`ritr-compare`) to the finest fixed rung (with `--accuracy-until T` over
the frames up to time T only: where the finest rung is a converged reference; the distance over
time is kept whole). The headline: the coarsest fixed
rung at least as accurate as r-ITR, r-ITR's time and memory ratios to it, and the sentence of
time to accuracy (scripts/accuracy_front.py): whether r-ITR reaches the accuracy of the finest
rung it matches in less time, and whether it is faster than a fixed mesh of its accuracy
interpolated between the rungs. With `--accuracy energy`
(statics) the runs are ranked by their final energy instead: each minimises the same potential
over a conforming space of deformations, so the lower equilibrium is the more accurate one.

`--ritr-rungs` adds r-ITR runs on refined meshes, `--ritr-variant NAME PATH=VALUE...` an r-ITR run
on the scene's own mesh with those entries changed (e.g. the deep punch with its base's reference
nodes held), and `--draws NAME...` has the headline judge r-ITR by the mean distance of its run and
of those variants, repeats of it under perturbations at round-off (at its run's time); `--mpirun-from K` runs the fixed rungs of K and more refinements on `--ranks` processes (`mpirun`,
doc/parallel.md), their memory the sum of the processes' peaks; `--pass-below` and
`--corner-touch` measure the last frame
(scripts/frame_metrics.py). With `--pass-below` each fixed rung also records r-ITR's mean
Hausdorff distance to it (`ritr_distance`, up to `--accuracy-until` when given: whether the ladder
moves toward r-ITR as it refines), and the headline sets r-ITR that passes against the coarsest
fixed rung that passes. Every run of a dynamic scene also records its kinetic energy in each
output frame (`kinetic_energy_over_time`), and with `--end-heights` the heights of its two ends
(`end_heights_over_time`). `--quick` runs two steps of r-ITR and of the two
coarsest rungs, so that a scene cannot rot unnoticed. `--timing-repeats N` times every run
shorter than ten seconds as the fastest of N (runs under a second move by up to a third between
sittings). The exit code is 1 if any run failed or
broke an invariant, or if `--require-lower-energy` finds an r-ITR run not below the fixed mesh
of its size (the JSON is written first: a failing run stays in the results).
"""
import argparse
from collections import defaultdict
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from accuracy_front import verdict  # noqa: E402
from frame_metrics import centroid_heights, corner_distances, end_heights, kinetic_energies, lowest_point  # noqa: E402
from prm_variant import entries, write_variant  # noqa: E402

DEFAULT_DENSITY = 1000.0  # Material N/density when a scene sets none (ritr --print-parameters)


def scene_name(scene):
    """The scene's path relative to the repository, whatever folder the runner started in."""
    return os.path.relpath(os.path.abspath(scene), os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))


def measure(command, log_path):
    """(exit code, wall seconds, peak RSS in bytes) of one process."""
    start = time.monotonic()
    with open(log_path, "w") as log:
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(process.pid, 0)
    return os.waitstatus_to_exitcode(status), time.monotonic() - start, usage.ru_maxrss * 1024


def body_sections(text):
    return sorted({path.split("/")[0] for path in entries(text) if path.startswith("Body ")}) or ["Body 0"]


def rung_overrides(scene_text, k, adaptivity, factor=1):
    """The overrides of rung k: adaptivity on or off, every body refined k more times and, for a
    factor above 1, its `subdivisions` multiplied by it (rungs between the powers of two)."""
    settings = entries(scene_text)
    overrides = {"Adaptivity/enabled": "true" if adaptivity else "false"}
    for body in body_sections(scene_text):
        overrides[f"{body}/refinements"] = str(int(settings.get(f"{body}/refinements", "0")) + k)
        if factor != 1:
            if f"{body}/subdivisions" not in settings:
                raise SystemExit(f"ladder: {body} has no `subdivisions` to multiply (--fixed-subdivide)")
            counts = [int(n) * factor for n in settings[f"{body}/subdivisions"].split(",")]
            overrides[f"{body}/subdivisions"] = ", ".join(map(str, counts))
    return overrides


def material_densities(scene_text):
    """{material id: density} of a scene (ritr's default density where the scene sets none)."""
    found = entries(scene_text)
    return defaultdict(lambda: DEFAULT_DENSITY,
                       {int(path.split()[1].split("/")[0]): float(value) for path, value in found.items()
                        if path.startswith("Material ") and path.endswith("/density")})


def run_entries(prm_text):
    """The entries that decide what a run computes: a fixed-mesh run (adaptivity off) leaves the
    other `Adaptivity` entries unread, so a scene's new outer-solve settings do not make its
    fixed rungs stale; the output directory is where the ladder finds the run, however --work
    was spelled; the Newton cap only decides where a run stops, so a run stopped on it resumes
    with a larger one (as `ritr --resume` does)."""
    found = entries(prm_text)
    found.pop("output directory", None)
    found.pop("Solver/max iterations", None)
    if found.get("Adaptivity/enabled", "false").strip().lower() in ("false", "0", "no"):
        found = {k: v for k, v in found.items() if not k.startswith("Adaptivity/") or k == "Adaptivity/enabled"}
    return found


def earlier_run(measured, prm_text, directory):
    """What an earlier ladder left of a run in the same work directory (`--reuse`): "finished"
    with its recorded measurement when it ran the same input to its end, "stopped" when it left a
    checkpoint to resume from, else None (run it afresh). The same input is the same entries
    (`run_entries`): an edited comment in the scene does not cost a rerun of hours."""
    try:
        with open(measured) as f:
            earlier = json.load(f)
    except (OSError, ValueError):
        return None
    if run_entries(earlier.get("prm", "")) != run_entries(prm_text):
        return None
    try:
        with open(os.path.join(directory, "summary.json")) as f:
            complete = json.load(f).get("complete", False)
    except (OSError, ValueError):
        complete = False
    if complete and earlier.get("exit_code") == 0:
        return "finished", earlier
    if os.path.exists(os.path.join(directory, "checkpoint.bin")):
        return "stopped", earlier
    return None


def run_rung(args, scene_text, name, overrides, work, processes=1):
    directory = os.path.join(work, name)
    overrides = dict(overrides, **{"output directory": directory})
    if args.quick:
        step = float(entries(scene_text).get("time step", "0.01"))
        overrides["end time"] = repr(2 * step)
        overrides["output every"] = "1"
    prm = write_variant(args.scene, overrides, os.path.join(work, name + ".prm"))
    command = [args.ritr, prm]
    if processes > 1:
        command = ["mpirun", "--oversubscribe", "-np", str(processes)] + command
    measured = os.path.join(work, name + ".measured.json")
    with open(prm) as f:
        prm_text = f.read()
    earlier = earlier_run(measured, prm_text, directory) if args.reuse else None
    if earlier and earlier[0] == "finished":
        code, wall, rss = (earlier[1][key] for key in ("exit_code", "wall_seconds", "peak_rss_bytes"))
        print(f"ladder: {name}: the finished run in {directory} is reused", flush=True)
    else:
        with open(measured, "w") as f:  # written first, so that a stopped run can be resumed
            json.dump({"prm": prm_text}, f)
        if earlier:  # a stopped run goes on from its checkpoint; its times add up in summary.json
            print(f"ladder: {name}: resuming the stopped run in {directory}", flush=True)
            command = command + ["--resume"]
        code, wall, rss = measure(command, os.path.join(work, name + (".resumed.log" if earlier else ".log")))
        with open(measured, "w") as f:
            json.dump({"prm": prm_text, "exit_code": code, "wall_seconds": wall, "peak_rss_bytes": rss}, f)
    run = {"name": name, "exit_code": code, "wall_seconds": wall, "peak_rss_bytes": rss, "directory": directory}
    if processes > 1:
        run["mpi_ranks"] = processes
    try:
        with open(os.path.join(directory, "summary.json")) as f:
            summary = json.load(f)
        for key in ("complete", "n_vertices", "final_energy", "total_newton_iterations", "total_outer_iterations",
                    "total_wall_seconds", "invariant_violations", "failure"):
            if key in summary:
                run[key] = summary[key]
        if processes > 1 and "peak_rss_bytes_per_process" in summary:
            run["peak_rss_bytes"] = sum(summary["peak_rss_bytes_per_process"])  # wait4 sees one process
    except (OSError, ValueError) as e:
        run["failure"] = f"no summary.json: {e}"
    repeats, timed = getattr(args, "timing_repeats", 1), 1
    if earlier and earlier[0] == "finished" and "fastest_own_seconds" in earlier[1]:
        run.update(total_wall_seconds=earlier[1]["fastest_own_seconds"], timing_repeats=earlier[1]["timing_repeats"])
        timed = run["timing_repeats"]
    # A short run timed on fewer runs than asked (a fresh one, one reused from a ladder without
    # repeats, a resumed one whose time sums its parts) gets the repeats it lacks.
    if (repeats > timed and not args.quick and processes == 1 and code == 0
            and run.get("total_wall_seconds", SHORT_RUN_SECONDS) < SHORT_RUN_SECONDS):
        scratch = os.path.join(work, name + ".repeat")
        repeat_prm = write_variant(args.scene, dict(overrides, **{"output directory": scratch}), scratch + ".prm")
        run["timing_repeats"] = timed
        fastest_of_repeats(run, [args.ritr, repeat_prm], scratch, repeats - timed)
        with open(measured, "w") as f:
            json.dump({"prm": prm_text, "exit_code": code, "wall_seconds": run["wall_seconds"], "peak_rss_bytes": rss,
                       "fastest_own_seconds": run["total_wall_seconds"], "timing_repeats": run["timing_repeats"]}, f)
    print(f"ladder: {name}: exit {code}, {run.get('n_vertices', '?')} vertices, {run['wall_seconds']:.1f} s, "
          f"{rss / 2**20:.0f} MiB", flush=True)
    return run


# Runs shorter than this (their own time) are timed as the fastest of --timing-repeats runs.
SHORT_RUN_SECONDS = 10.0


def fastest_of_repeats(run, command, scratch, more):
    """A run of under a second moves by up to a third between sittings, enough to move a verdict
    of time to accuracy: with --timing-repeats the run is repeated `more` times into the directory
    `scratch` (removed afterwards: the run's own outputs stay as they are), its wall and own times
    become the fastest of all and `timing_repeats` counts the runs they were taken over. A repeat
    that fails or ends at another energy (a run is deterministic on one process) stops the
    repeats and is recorded in `timing_repeat_failure`."""
    walls, own = [run["wall_seconds"]], [run["total_wall_seconds"]]
    for _ in range(more):
        code, wall, _ = measure(command, scratch + ".log")
        try:
            with open(os.path.join(scratch, "summary.json")) as f:
                summary = json.load(f)
        except (OSError, ValueError):
            summary = {}
        if code != 0 or summary.get("final_energy") != run.get("final_energy"):
            run["timing_repeat_failure"] = f"a repeat ended otherwise (exit {code}, energy {summary.get('final_energy')})"
            print(f"ladder: {run['name']}: {run['timing_repeat_failure']}; timed on {len(own)} runs", flush=True)
            break
        walls.append(wall)
        own.append(summary["total_wall_seconds"])
    shutil.rmtree(scratch, ignore_errors=True)
    run.update(wall_seconds=min(walls), total_wall_seconds=min(own), timing_repeats=run["timing_repeats"] + len(own) - 1)


def hausdorff_until(per_frame, until):
    """Mean and largest Hausdorff distance of ritr-compare's frames at times up to `until` (with
    round-off in the time), or None without such a frame."""
    ranked = [f["hausdorff"] for f in per_frame if f["time"] <= until + 1e-9 * max(1.0, abs(until))]
    return (sum(ranked) / len(ranked), max(ranked)) if ranked else None


def compare(args, run, reference, until=None):
    """Adds ritr-compare's distances of `run` to `reference`; with `until`, the mean and largest
    Hausdorff distance are of the frames up to that time."""
    result = subprocess.run([args.compare, run["directory"], reference["directory"]], capture_output=True, text=True)
    if result.returncode != 0:
        run["compare_failure"] = result.stderr.strip()
        return
    c = json.loads(result.stdout)
    if until is not None:
        window = hausdorff_until(c["per_frame"], until)
        if window is None:
            run["compare_failure"] = f"no frame at or before t = {until:g}"
            return
        c["mean_hausdorff"], c["max_hausdorff"] = window
    run.update(mean_hausdorff=c["mean_hausdorff"], max_hausdorff=c["max_hausdorff"],
               centroid_distance_mean=c["centroid_distance_mean"],
               hausdorff_over_time=[[f["time"], f["hausdorff"]] for f in c["per_frame"]])


def write_result(result, out, echo=True):
    """Writes a result as JSON to the file `out` (its folder created), or with `echo` to stdout."""
    text = json.dumps(result, indent=1)
    if out:
        os.makedirs(os.path.dirname(os.path.abspath(out)), exist_ok=True)
        with open(out, "w") as f:
            f.write(text + "\n")
    elif echo:
        print(text)


def failed_runs(runs):
    """The names of the runs that failed or broke an invariant."""
    return [r["name"] for r in runs if r["exit_code"] != 0 or r.get("invariant_violations")]


def is_ritr(run):
    # Results written before runs carried "adaptivity" name their r-ITR runs "ritr...".
    return run.get("adaptivity", run["name"].startswith("ritr"))


def fixed_runs(runs):
    return [r for r in runs if not is_ritr(r)]


def run_seconds(run):
    """A run's own wall time (set-up, steps, output) from its summary.json: the program's start-up,
    the same for every run and most of a small one's process time, is left out."""
    return run.get("total_wall_seconds", run["wall_seconds"])


def cost_ratios(ritr, fixed, baseline_rss):
    memory = lambda r: max(r["peak_rss_bytes"] - baseline_rss, 1)
    return {"matching_fixed": fixed["name"],
            "vertex_ratio": fixed.get("n_vertices", 0) / max(ritr.get("n_vertices", 1), 1),
            "time_ratio_ritr_to_fixed": run_seconds(ritr) / run_seconds(fixed),
            "time_note": "the runs' own wall times (summary.json), without the program's start-up",
            "memory_ratio_ritr_to_fixed": memory(ritr) / memory(fixed),
            "memory_note": "peak RSS minus the start-up baseline of `ritr --help`"}


def over_draws(ritr, runs, draws):
    """r-ITR as judged over draws: a scene whose outcome moves with round-off (the masticator's
    release) is judged by the mean distance of its run and of the named variants that repeat it
    under perturbations at round-off; its time stays the scene's run's (the draws may have run
    beside other work). Returns the run and the names averaged, or the run alone without two
    measured runs."""
    if not draws:
        return ritr, []
    by_name = {r["name"]: r for r in runs}
    missing = [name for name in draws if name not in by_name]
    if missing:
        raise ValueError("--draws: no run " + ", ".join(missing))
    measured = lambda r: "mean_hausdorff" in r and r["exit_code"] == 0
    # A failed draw fails the ladder (failed_runs); the mean is over those measured, named in the result.
    drawn = [r for r in [ritr] + [by_name[name] for name in draws] if measured(r)]
    if not measured(ritr) or len(drawn) < 2:
        return ritr, []
    return dict(ritr, mean_hausdorff=sum(r["mean_hausdorff"] for r in drawn) / len(drawn)), [r["name"] for r in drawn]


def hausdorff_headline(runs, reference, baseline_rss, draws=()):
    ritr, drawn = over_draws(runs[0], runs, draws)
    # A rung that stopped early is compared on its frames only: no fair accuracy or cost figure.
    candidates = [r for r in fixed_runs(runs) if r is not reference and "mean_hausdorff" in r and r["exit_code"] == 0]
    if reference["exit_code"] != 0:
        return {"matching_fixed": None, "why": f"the reference rung did not finish (exit {reference['exit_code']})"}
    if "mean_hausdorff" not in ritr or ritr["exit_code"] != 0:
        return {"matching_fixed": None, "why": "r-ITR has no accuracy figure (failed run or comparison)"}
    matching = next((r for r in candidates if r["mean_hausdorff"] <= ritr["mean_hausdorff"]), None)
    if matching is None:
        matching, why = reference, "no coarser fixed rung is as accurate; the reference rung is"
    else:
        why = "coarsest fixed rung with mean Hausdorff <= r-ITR's"
    timed = lambda r: dict(r, seconds=run_seconds(r))
    result = dict(cost_ratios(ritr, matching, baseline_rss), why=why,
                  time_to_accuracy=verdict(timed(ritr), [timed(r) for r in candidates]) if candidates else None)
    if drawn:
        result.update(draws=drawn, ritr_mean_hausdorff=ritr["mean_hausdorff"],
                      draws_note="r-ITR's accuracy is the mean over these runs; its time the first's")
    return result


def energy_headline(runs, baseline_rss):
    """Statics: every run minimises the same potential over a conforming space of deformations,
    so a lower final energy is the more accurate equilibrium (the paper's Figs 16 and 18)."""
    ritr = runs[0]
    finished = [r for r in fixed_runs(runs) if r["exit_code"] == 0 and "final_energy" in r]
    if ritr["exit_code"] != 0 or "final_energy" not in ritr:
        return {"matching_fixed": None, "why": "r-ITR did not finish"}
    if not finished:
        return {"matching_fixed": None, "why": "no fixed rung finished"}
    matching = next((r for r in finished if r["final_energy"] <= ritr["final_energy"]), None)
    if matching is None:
        matching = finished[-1]
        why = "r-ITR's final energy is below every fixed rung's; ratios against the finest finished rung"
    else:
        why = "coarsest fixed rung with final energy <= r-ITR's"
    return dict(cost_ratios(ritr, matching, baseline_rss), why=why,
                energy_ritr=ritr["final_energy"], energy_fixed=matching["final_energy"])


def further_than_every_rung(headline):
    """Whether the headline's r-ITR is further from the reference than every other fixed rung (its
    time-to-accuracy verdict matched none): on a gap scene, r-ITR passes but moves otherwise."""
    verdict = headline.get("time_to_accuracy")
    return verdict is not None and verdict.get("matched") is None


def gap_headline(runs, reference, baseline_rss, draws=()):
    """Scenes with a gap (`--pass-below`): whether a run passes is what it must get right first, so
    when r-ITR passes it is set against the coarsest fixed rung that passes too; its distances to
    the reference (`time_to_accuracy`) stay in the headline beside that."""
    ritr = runs[0]
    if not ritr.get("passes") or reference["exit_code"] != 0:
        return hausdorff_headline(runs, reference, baseline_rss, draws)
    if not reference.get("passes"):
        return {"matching_fixed": None,
                "why": "r-ITR passes the gap but the finest fixed rung locks in it, so no rung is a reference for accuracy"}
    result = hausdorff_headline(runs, reference, baseline_rss, draws)
    first = next(r for r in fixed_runs(runs) if r.get("passes") and r["exit_code"] == 0)
    result.update(cost_ratios(ritr, first, baseline_rss), why="coarsest fixed rung that passes the gap, as r-ITR does")
    return result


def headline(args, runs, reference, baseline_rss):
    draws = [f"ritr_{name}" for name in args.draws]
    if args.accuracy == "energy":
        return energy_headline(runs, baseline_rss)
    if args.pass_below is not None:
        return gap_headline(runs, reference, baseline_rss, draws)
    return hausdorff_headline(runs, reference, baseline_rss, draws)


def summary(result, work):
    """One line comparing r-ITR with the fixed mesh of the same size, and where the runs are."""
    ritr, fixed = result["runs"][0], fixed_runs(result["runs"])[0]
    reference = next(r for r in result["runs"] if r["name"] == result["reference"])
    accuracy = (f"; mean Hausdorff distance to the fixed mesh of {reference.get('n_vertices', '?'):,} vertices: "
                f"r-ITR {ritr['mean_hausdorff']:.2e}, fixed {fixed['mean_hausdorff']:.2e}"
                if "mean_hausdorff" in ritr and "mean_hausdorff" in fixed else "")
    line = (f"r-ITR on {ritr.get('n_vertices', '?'):,} vertices: energy {ritr.get('final_energy', float('nan')):.6g}, "
            f"{run_seconds(ritr):.2f} s; fixed mesh of the same size: energy "
            f"{fixed.get('final_energy', float('nan')):.6g}, {run_seconds(fixed):.2f} s{accuracy}")
    verdict_of = result["headline"].get("time_to_accuracy")
    if verdict_of:
        line += "\n" + verdict_of["sentence"]
    where = (f"results: {os.path.join(work, 'ritr')} and {os.path.join(work, fixed['name'])} (open solution.pvd and "
             f"reference.pvd in ParaView); pictures: scripts/render.py {os.path.join(work, 'ritr')}")
    return line + "\n" + where


def main():
    build = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build")
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("scene")
    p.add_argument("--fixed", type=int, nargs="+", required=True, help="refinements of the fixed rungs")
    p.add_argument("--fixed-subdivide", type=int, nargs="+", default=[], metavar="M",
                   help="further fixed rungs (not in --quick) with every body's subdivisions multiplied by M")
    p.add_argument("--set", action="append", default=[], metavar="PATH=VALUE",
                   help="override for every run, e.g. 'Adaptivity/epsilon r=1e-6'")
    p.add_argument("--ritr-rungs", type=int, nargs="+", default=[0],
                   help="refinements of r-ITR runs besides the scene's own mesh (r-ITR under refinement)")
    p.add_argument("--ritr-variant", nargs="+", action="append", default=[], metavar="NAME PATH=VALUE",
                   help="an extra r-ITR run ritr_NAME on the scene's own mesh with the entries that follow "
                        "the name overridden")
    p.add_argument("--mpirun-from", type=int, metavar="K",
                   help="fixed rungs of K and more refinements run under mpirun on --ranks processes")
    p.add_argument("--ranks", type=int, default=2, help="processes of the --mpirun-from rungs")
    p.add_argument("--quick", action="store_true")
    p.add_argument("--accuracy", choices=("hausdorff", "energy"), default="hausdorff",
                   help="what ranks the runs: mean Hausdorff distance to the finest rung (dynamics) or the "
                        "final energy (statics: the lower equilibrium energy is the better one)")
    p.add_argument("--accuracy-until", type=float, metavar="T",
                   help="Hausdorff accuracy over the frames up to time T only (where the finest rung is converged)")
    p.add_argument("--pass-below", type=float, metavar="Y",
                   help="a run passes (an obstacle's gap) when its lowest deformed point ends below height Y")
    p.add_argument("--corner-touch", type=float, metavar="D",
                   help="for each obstacle vertex within D of a body at the end, the distance to the nearest "
                        "deformed mesh vertex (2D; the paper's stamping figure)")
    p.add_argument("--end-heights", action="store_true",
                   help="record the height of the bodies' two reference ends in every frame (2D dynamics: "
                        "when a bar's ends come off the teeth)")
    p.add_argument("--draws", nargs="+", default=[], metavar="NAME",
                   help="--ritr-variant names that repeat the scene's run under a perturbation at round-off: the "
                        "headline judges r-ITR by the mean distance of its run and theirs (a scene whose outcome "
                        "moves with round-off), at its run's time")
    p.add_argument("--require-lower-energy", action="store_true",
                   help="fail unless every r-ITR run ends with a lower energy than the fixed rung of its size")
    p.add_argument("--out", help="result JSON (default: stdout)")
    p.add_argument("--summary", action="store_true",
                   help="print one line comparing r-ITR with the fixed mesh of its size instead of the JSON")
    p.add_argument("--work", help="directory for the runs (default: a temporary one)")
    p.add_argument("--timing-repeats", type=int, default=1, metavar="N",
                   help=f"time each run shorter than {SHORT_RUN_SECONDS:g} s as the fastest of N runs")
    p.add_argument("--reuse", action="store_true",
                   help="runs that an earlier ladder in --work finished with the same entries are taken as they "
                        "are; those it left stopped are resumed from their checkpoints")
    p.add_argument("--ritr", default=os.path.join(build, "ritr"))
    p.add_argument("--compare", default=os.path.join(build, "ritr-compare"))
    args = p.parse_args()

    with open(args.scene) as f:
        scene_text = f.read()
    if any(len(variant) < 2 for variant in args.ritr_variant):
        p.error("--ritr-variant: a name and at least one PATH=VALUE")
    for setting in args.set + [s for variant in args.ritr_variant for s in variant[1:]]:
        if "=" not in setting:
            p.error(f"'{setting}' is not PATH=VALUE")
    if any(variant[0].startswith("r") and variant[0][1:].isdigit() for variant in args.ritr_variant):
        p.error("--ritr-variant: names rN are the refined r-ITR runs'")
    unknown_draws = set(args.draws) - {variant[0] for variant in args.ritr_variant}
    if unknown_draws:
        p.error("--draws: not a --ritr-variant: " + ", ".join(sorted(unknown_draws)))
    common = dict(item.split("=", 1) for item in args.set)
    if args.mpirun_from is not None:  # containers and CI machines often run as root
        os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
        os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    rungs = sorted(args.fixed)[:2] if args.quick else sorted(args.fixed)
    work = args.work or tempfile.mkdtemp(prefix="ladder-")
    os.makedirs(work, exist_ok=True)
    _, _, baseline_rss = measure([args.ritr, "--help"], os.path.join(work, "baseline.log"))

    def rung(name, k, adaptivity, extra=None, factor=1):
        overrides = {**common, **rung_overrides(scene_text, k, adaptivity, factor), **(extra or {})}
        shared = not adaptivity and args.mpirun_from is not None and k >= args.mpirun_from
        processes = args.ranks if shared else 1
        return dict(run_rung(args, scene_text, name, overrides, work, processes), refinements=k, subdivision_factor=factor,
                    adaptivity=adaptivity, **({"overrides": extra} if extra else {}))

    # runs[0] is r-ITR on the scene's own mesh, the fixed rungs follow from coarsest to finest (the
    # finest is the reference), then further r-ITR rungs (paper Fig. 20) and variants.
    ritr = rung("ritr", 0, True)
    fixed = [rung(f"fixed_r{k}", k, False) for k in rungs]
    if not args.quick:
        fixed += [rung(f"fixed_x{m}", 0, False, factor=m) for m in sorted(set(args.fixed_subdivide) - {1})]
    runs = [ritr] + sorted(fixed, key=lambda r: r.get("n_vertices", 0))
    reference = runs[-1]
    if not args.quick:
        runs += [rung(f"ritr_r{k}", k, True) for k in sorted(set(args.ritr_rungs) - {0})]
    runs += [rung(f"ritr_{name}", 0, True, dict(s.split("=", 1) for s in settings))
             for name, *settings in args.ritr_variant]
    dynamic = entries(scene_text).get("mode", "dynamic") == "dynamic"
    densities = material_densities(scene_text)
    for run in runs:
        if run is not reference:
            compare(args, run, reference, until=args.accuracy_until)
        if dynamic and os.path.exists(os.path.join(run["directory"], "solution.pvd")):
            run["kinetic_energy_over_time"] = kinetic_energies(run["directory"], densities)
            if args.end_heights:
                run["end_heights_over_time"] = end_heights(run["directory"])
        if args.pass_below is not None and run["exit_code"] == 0:
            run["lowest_point"] = lowest_point(run["directory"])
            run["passes"] = run["lowest_point"] < args.pass_below
            run["centroid_over_time"] = centroid_heights(run["directory"])
            if not run["adaptivity"] and ritr["exit_code"] == 0:
                # Whether the fixed ladder moves toward r-ITR as it refines (paper Fig. 2: only
                # the finest fixed mesh matches r-ITR's motion). r-ITR's distance to the reference
                # is its own accuracy, measured above.
                to_run = ritr
                if run is not reference:
                    to_run = {"directory": ritr["directory"]}
                    compare(args, to_run, run, until=args.accuracy_until)
                if "compare_failure" in to_run:
                    run["ritr_distance_failure"] = to_run["compare_failure"]
                else:
                    run["ritr_distance"] = to_run["mean_hausdorff"]
        if args.corner_touch is not None and run["exit_code"] == 0:
            run["corner_distances"] = corner_distances(run["directory"], args.corner_touch)

    result = {"scene": scene_name(args.scene), "quick": args.quick, "overrides": common,
              "pass_below": args.pass_below, "corner_touch": args.corner_touch,
              "baseline_rss_bytes": baseline_rss, "reference": reference["name"], "runs": runs,
              "accuracy": args.accuracy, "accuracy_until": args.accuracy_until,
              "headline": headline(args, runs, reference, baseline_rss)}
    for run in runs:
        run.pop("directory")
    if args.summary:
        print(summary(result, os.path.relpath(work)))
    write_result(result, args.out, echo=not args.summary)
    bad = failed_runs(runs)
    if bad:
        print("ladder: failed or broke an invariant: " + ", ".join(bad), file=sys.stderr)
        return 1
    if args.require_lower_energy:
        same_size = {r["refinements"]: r for r in fixed_runs(runs) if r["subdivision_factor"] == 1}
        higher = [f"{r['name']} {r['final_energy']:.8g} >= {same_size[r['refinements']]['final_energy']:.8g}"
                  for r in runs if r["adaptivity"] and r["refinements"] in same_size
                  and r["final_energy"] >= same_size[r["refinements"]]["final_energy"]]
        if higher:
            print("ladder: r-ITR not below the fixed mesh of its size: " + ", ".join(higher), file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
