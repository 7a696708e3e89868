#!/usr/bin/python3
"""Fixed-mesh runs shared among processes: one against N, CHOLMOD against Trilinos' solvers.

    scripts/distributed_benchmark.py [--ranks N] [--quick] [--out doc/benchmarks/distributed.json]

Runs each scene of SCENES serially (CHOLMOD), and under `mpirun -np 1` and `mpirun -np N` with
each distributed solver (`Solver/distributed solver` = direct: MUMPS; amg: CG with ML's
multigrid), one run after the other, and records from each run's summary.json its wall time
(without start-up), Newton iterations, linear-solve seconds and peak memory of every process,
and how far its final positions are from the serial run's. Ratios are taken within this one
sitting: each run's speed-up over the serial run and, per solver, N processes over one; the
AMG solver's time over the direct one's on N processes. `--quick` runs the first step only.
The exit code is 1 if a run fails, breaks an invariant, or its Newton iterations differ from
the serial run's by more than 10 %.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ladder import measure, scene_name, write_result  # noqa: E402
from prm_variant import write_variant  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
SCENES = ["prm/benchmark/distributed_statics_2d.prm", "prm/benchmark/distributed_dynamics_3d.prm"]
SOLVERS = ["direct", "amg"]


def last_positions(directory):
    """{column: values} of the run's last nodes-NNNNN.csv (its deformed positions x_*)."""
    last = sorted(f for f in os.listdir(directory) if f.startswith("nodes-"))[-1]
    with open(os.path.join(directory, last)) as f:
        header = f.readline().strip().split(",")
        rows = [[float(v) for v in line.split(",")] for line in f if line.strip()]
    return [[row[i] for i, name in enumerate(header) if name.startswith("x_")] for row in rows]


def run(args, scene, name, ranks, solver, work):
    directory = os.path.join(work, name)
    overrides = {"output directory": directory, "write nodal csv": "true"}
    if solver:
        overrides["Solver/distributed solver"] = solver
    if args.quick:
        overrides["end time"] = "0.5" if "statics" in scene else "0.01"
    prm = write_variant(os.path.join(ROOT, scene), overrides, os.path.join(work, name + ".prm"))
    command = [args.ritr, prm]
    if ranks > 0:
        command = ["mpirun", "--oversubscribe", "-np", str(ranks)] + command
    code, wall, _ = measure(command, os.path.join(work, name + ".log"))
    result = dict(name=name, processes=max(ranks, 1), mpirun=ranks > 0, solver=solver or "cholmod", exit_code=code,
                  wall_seconds_outside=wall)
    summary = os.path.join(directory, "summary.json")
    if code == 0 and os.path.exists(summary):
        with open(summary) as f:
            s = json.load(f)
        result.update({k: s[k] for k in ("n_vertices", "steps", "total_wall_seconds", "total_newton_iterations",
                                         "linear_solve_seconds", "peak_rss_bytes_per_process",
                                         "invariant_violations")})
        result["positions"] = last_positions(directory)
    print(f"{name}: exit {code}, {result.get('total_wall_seconds', float('nan')):.1f} s, "
          f"{result.get('total_newton_iterations')} Newton iterations", flush=True)
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--ritr", default=os.path.join(ROOT, "build", "ritr"))
    parser.add_argument("--out", default="")
    args = parser.parse_args()
    # Open MPI refuses to start as root unless told that it is meant (containers, CI).
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    failed = False
    scenes = []
    with tempfile.TemporaryDirectory(prefix="ritr-distributed-") as work:
        for scene in SCENES:
            stem = os.path.splitext(os.path.basename(scene))[0]
            runs = [run(args, scene, stem + "-serial", 0, None, work)]
            runs += [run(args, scene, f"{stem}-{ranks}-{solver}", ranks, solver, work)
                     for solver in SOLVERS for ranks in (1, args.ranks)]
            serial = runs[0]
            for r in runs:
                ok = r["exit_code"] == 0 and "positions" in r and not r["invariant_violations"]
                if ok and r is not serial and "positions" in serial:
                    r["max_position_difference"] = max(abs(a - b) for p, q in zip(r["positions"], serial["positions"])
                                                       for a, b in zip(p, q))
                    r["speed_up"] = serial["total_wall_seconds"] / r["total_wall_seconds"]
                    its, its_serial = r["total_newton_iterations"], serial["total_newton_iterations"]
                    ok = abs(its - its_serial) <= 0.1 * its_serial
                failed |= not ok
            for r in runs:
                r.pop("positions", None)
            timed = {(r["solver"], r["processes"]): r["total_wall_seconds"] for r in runs[1:] if "total_wall_seconds" in r}
            entry = dict(scene=scene_name(scene), runs=runs)
            for solver in SOLVERS:
                if (solver, 1) in timed and (solver, args.ranks) in timed:
                    entry[solver + "_parallel_speed_up"] = timed[(solver, 1)] / timed[(solver, args.ranks)]
            if ("amg", args.ranks) in timed and ("direct", args.ranks) in timed:
                entry["amg_over_direct"] = timed[("amg", args.ranks)] / timed[("direct", args.ranks)]
            scenes.append(entry)
    result = dict(processes=args.ranks, quick=args.quick, cores=os.cpu_count(), scenes=scenes)
    write_result(result, args.out)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
