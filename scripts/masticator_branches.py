#!/usr/bin/python3
"""Which branch a fine mesh takes from r-ITR's states: fixed meshes started from r-ITR frames.

    scripts/masticator_branches.py SCENE [--start T] [--refine K] [--iterations N] [--out JSON]
                                   [--work DIR] [--reuse] [--set PATH=VALUE ...]

Runs, one after another: the fixed reference (every body's subdivisions times 5), r-ITR as the
scene and the --set overrides give it, and with N outer iterations per step, and then, from each
r-ITR run's frame at time T, a fixed mesh on that frame's moved reference mesh refined K times
(scripts/frame_mesh.py) started from exactly the frame's state (`start from`), and the same
frame's mesh unrefined.
Every run is measured against the reference (mean Hausdorff distance, by frame) and each
restarted run also against the r-ITR run it started from, so that the result says whether a
finer mesh follows an r-ITR run's path from T or goes its own way (doc/benchmarks.md,
Masticator). The result has the ladder's layout (scripts/ladder.py).
"""
import argparse
import hashlib
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from frame_metrics import kinetic_energies, series  # noqa: E402
from ladder import compare, failed_runs, material_densities, run_rung, rung_overrides, write_result  # noqa: E402
from prm_variant import entries  # noqa: E402


BITE_END = 5.0  # the teeth are closed until t = 5 (prm/paper/masticator.prm)


def mean_after(run, time):
    """Mean Hausdorff distance to the reference over the frames after `time`."""
    values = [h for t, h in run.get("hausdorff_over_time", []) if t > time + 1e-9]
    return sum(values) / len(values) if values else float("nan")


def frame_at(directory, time):
    """(time, path) of a run's frame nearest to `time`."""
    return min(series(directory), key=lambda frame: abs(frame[0] - time))


def frame_mesh_path(work, source_name, frame):
    """Where the mesh of a source run's frame goes: named by the frame's content, so that a restart
    from a frame that changed (its source run ran again) has other entries and `--reuse` runs it
    again instead of keeping the restart from the old frame."""
    with open(frame, "rb") as f:
        digest = hashlib.sha256(f.read()).hexdigest()[:16]
    return os.path.join(work, f"{source_name}_frame_{digest}.msh")


def main():
    build = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "build")
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("--start", type=float, default=4.4, help="time of the r-ITR frames the fixed meshes start from")
    p.add_argument("--refine", type=int, default=2, help="refinements of the frame's mesh for the fine restart")
    p.add_argument("--iterations", type=int, default=3, help="outer iterations per step of the second r-ITR run")
    p.add_argument("--set", action="append", default=[], metavar="PATH=VALUE", help="override for every run")
    p.add_argument("--out", help="result JSON (default: stdout)")
    p.add_argument("--work", help="directory for the runs (default: a temporary one)")
    p.add_argument("--reuse", action="store_true", help="as scripts/ladder.py --reuse")
    p.add_argument("--ritr", default=os.path.join(build, "ritr"))
    p.add_argument("--compare", default=os.path.join(build, "ritr-compare"))
    args = p.parse_args()
    args.quick = False

    with open(args.scene) as f:
        scene_text = f.read()
    bodies = {path.split("/")[0] for path in entries(scene_text) if path.startswith("Body ")}
    if len(bodies) > 1:
        p.error("a scene of one body (the restarts build it on one frame's mesh)")
    common = dict(item.split("=", 1) for item in args.set)
    # Absolute: the restarts name the frame mesh and frame in parameter files written there.
    work = os.path.abspath(args.work or tempfile.mkdtemp(prefix="branches-"))
    os.makedirs(work, exist_ok=True)

    def rung(name, k, adaptivity, extra=None, factor=1):
        overrides = {**common, **rung_overrides(scene_text, k, adaptivity, factor), **(extra or {})}
        return dict(run_rung(args, scene_text, name, overrides, work), refinements=k, subdivision_factor=factor,
                    adaptivity=adaptivity, **({"overrides": extra} if extra else {}))

    reference = rung("fixed_x5", 0, False, factor=5)
    ritr = rung("ritr", 0, True)
    more = rung(f"ritr_it{args.iterations}", 0, True, {"Adaptivity/max iterations": str(args.iterations)})
    runs = [reference, ritr, more]
    for source in (ritr, more):
        time, frame = frame_at(source["directory"], args.start)
        mesh = frame_mesh_path(work, source["name"], frame)
        subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)), "frame_mesh.py"),
                        frame, mesh], check=True)
        for k in sorted({0, args.refine}):
            restart = rung(f"fixed_r{k}_from_{source['name']}", k, False,
                           {"Body 0/shape": "file", "Body 0/file": mesh, "start from": frame})
            restart.update(source=source["name"], start_time=time)
            runs.append(restart)

    densities = material_densities(scene_text)
    by_name = {r["name"]: r for r in runs}
    for run in runs:
        if run is not reference:
            compare(args, run, reference)
        if "source" in run:
            from_source = {"directory": by_name[run["source"]]["directory"]}
            compare(args, from_source, run)
            run["source_hausdorff_over_time"] = from_source.get("hausdorff_over_time", [])
        run["kinetic_energy_over_time"] = kinetic_energies(run["directory"], densities)
    fine = [by_name[f"fixed_r{args.refine}_from_{source['name']}"] for source in (ritr, more)]
    after = [mean_after(run, BITE_END) for run in fine]
    sentence = (f"From the state of r-ITR at t = {args.start:g} the "
                f"{fine[0].get('n_vertices', 0):,}-vertex fixed mesh ends {after[0]:.3f} from {reference['name']} on "
                f"average after the bite (t > {BITE_END:g}); from that of r-ITR with {args.iterations} outer "
                f"iteration{'s' if args.iterations != 1 else ''} per step, {after[1]:.3f}.")
    result = {"scene": "masticator_branches", "quick": False, "overrides": common, "reference": reference["name"],
              "runs": [ritr, reference] + [r for r in runs if r not in (ritr, reference)], "accuracy": "hausdorff",
              "start": args.start, "headline": {"sentence": sentence}}
    for run in runs:
        run.pop("directory")
    write_result(result, args.out)
    bad = failed_runs(runs)
    if bad:
        print("masticator_branches: failed or broke an invariant: " + ", ".join(bad), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
