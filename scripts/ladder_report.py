#!/usr/bin/python3
"""Plots and a Markdown table of one ladder result (scripts/ladder.py).

    scripts/ladder_report.py RESULT.json [--plots DIR]

Prints the table to stdout and writes the plots beside the JSON (or into DIR): for a ladder
ranked by Hausdorff distance, NAME_hausdorff.png (distance to the reference rung over time, one
line per run) and NAME_cost.png (mean distance against wall time and against vertices); for one
ranked by energy (statics), NAME_energy.png (final energy against vertices, wall time and peak
memory: the paper's Fig. 16). r-ITR is marked in each. A ladder with a gap to pass
(`--pass-below`) over more than two frames also gets NAME_centroid.png, the height of each
run's area centroid over time. A dynamic ladder over more than two frames also gets
NAME_kinetic.png, each run's kinetic energy over time.
"""
import argparse
import json
import os
import statistics
import sys

import matplotlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ladder import fixed_runs, is_ritr, run_seconds  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def table(result):
    base = result["baseline_rss_bytes"]
    lines = ["| run | vertices | wall [s] | peak RSS - baseline [MiB] | Newton its | outer its | final energy "
             "| mean Hausdorff | max Hausdorff | exit |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in result["runs"]:
        if r["name"] == result["reference"]:
            accuracy = "reference | reference"
        elif "mean_hausdorff" in r:
            accuracy = f"{r['mean_hausdorff']:.3g} | {r['max_hausdorff']:.3g}"
        else:
            accuracy = "- | -"
        lines.append(f"| {r['name']} | {cost_cells(r, base)} | {r.get('final_energy', float('nan')):.6g} "
                     f"| {accuracy} | {r['exit_code']} |")
    if result.get("pass_below") is not None:
        lines += ["", f"Passes (lowest deformed point below y = {result['pass_below']:g}): " + ", ".join(
            f"{r['name']} {'passes' if r['passes'] else 'locks'} ({r['lowest_point']:.3f})"
            for r in result["runs"] if "passes" in r) + "."]
    if result.get("corner_touch") is not None:
        lines += ["", f"Obstacle corners within {result['corner_touch']:g} of a body, distance to the nearest mesh "
                  "vertex: " + "; ".join(
                      f"{r['name']} {len(r['corner_distances'])} corners, median "
                      f"{statistics.median(r['corner_distances'] or [0]):.2e}, max {max(r['corner_distances'], default=0):.2e}"
                      for r in result["runs"] if "corner_distances" in r) + "."]
    h = result["headline"]
    if not h.get("matching_fixed"):
        lines += ["", f"No headline: {h['why']}."]
    else:
        lines.append("")
        claim = "is compared with" if result.get("accuracy") == "energy" else "matches"
        lines.append(f"Headline: r-ITR {claim} `{h['matching_fixed']}` ({h['why']}): "
                     f"{h['vertex_ratio']:.1f}x its vertices, {cost_ratio_text(h, base)}.")
    return "\n".join(lines)


def cost_cells(run, base):
    """The table cells vertices | wall | peak RSS - baseline | Newton its | outer its of a run."""
    return (f"{run.get('n_vertices', '?'):,} | {run['wall_seconds']:.1f} | {(run['peak_rss_bytes'] - base) / 2**20:.0f} "
            f"| {run.get('total_newton_iterations', '-')} | {run.get('total_outer_iterations', '-')}")


def cost_ratio_text(headline, base):
    return (f"time ratio r-ITR/fixed {headline['time_ratio_ritr_to_fixed']:.2f}, memory ratio "
            f"{headline['memory_ratio_ritr_to_fixed']:.2f} ({headline['memory_note']}; baseline {base / 2**20:.0f} MiB)")


def plot_prefix(result_path, plots_directory):
    """DIR/NAME for the plots of RESULT.json: DIR is plots_directory or the JSON's folder."""
    directory = plots_directory or os.path.dirname(os.path.abspath(result_path))
    os.makedirs(directory, exist_ok=True)
    return os.path.join(directory, os.path.splitext(os.path.basename(result_path))[0])


def mark(ax, runs, x, y):
    """Fixed rungs as an orange line, r-ITR runs as green stars (joined when refined too)."""
    fixed = fixed_runs(runs)
    ax.plot([x(r) for r in fixed], [y(r) for r in fixed], "o-", color="tab:orange", label="fixed mesh")
    for r in fixed:
        ax.annotate(r["name"], (x(r), y(r)), fontsize=7)
    ritr = sorted((r for r in runs if is_ritr(r)), key=lambda r: r.get("n_vertices", 0))
    if ritr:
        ax.plot([x(r) for r in ritr], [y(r) for r in ritr], "*-", color="tab:green", markersize=14, label="r-ITR")


def cost_figure(path, runs, measures, y, ylabel, log_y):
    """One panel per cost measure (label, value of a run) with y against it, r-ITR marked."""
    fig, axes = plt.subplots(1, len(measures), figsize=(4.7 * len(measures), 4))
    for ax, (label, value) in zip(axes, measures):
        mark(ax, runs, value, y)
        ax.set_xscale("log")
        if log_y:
            ax.set_yscale("log")
        ax.set_xlabel(label)
        ax.set_ylabel(ylabel)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def energy_plot(result, prefix):
    """Paper Fig. 16: final energy against vertices, wall time and peak memory."""
    base = result["baseline_rss_bytes"]
    runs = [r for r in result["runs"] if "final_energy" in r and r["exit_code"] == 0]
    measures = (("vertices", lambda r: r["n_vertices"]), ("the run's own wall time [s]", run_seconds),
                ("peak RSS - baseline [MiB]", lambda r: max(r["peak_rss_bytes"] - base, 1) / 2**20))
    cost_figure(prefix + "_energy.png", runs, measures, lambda r: r["final_energy"],
                "final (equilibrium) energy", log_y=False)


def ladder_line_style(run):
    """r-ITR in bold green (its further rungs and variants dashed), fixed rungs thin."""
    label = f"{run['name']} ({run.get('n_vertices', '?')} v)"
    if not is_ritr(run):
        return dict(linewidth=1, label=label)
    return dict(color="tab:green", linewidth=2.5, linestyle="-" if run["name"] == "ritr" else "--", label=label)


def time_series_plot(runs, key, ylabel, path, line_style=ladder_line_style, level=None):
    """Each run's series `key` ([[time, value], ...]) over time; `level`, a value to pass, dotted."""
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    for r in runs:
        if r.get(key):
            ax.plot(*zip(*r[key]), **line_style(r))
    if level is not None:
        ax.axhline(level, color="black", linewidth=0.6, linestyle=":")
    ax.set_xlabel("time")
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def centroid_plot(runs, path, line_style=ladder_line_style, pass_below=None):
    """Each run's centroid height over time; a centroid height a run must pass marked dotted."""
    time_series_plot(runs, "centroid_over_time", "centroid height", path, line_style, pass_below)


def plots(result, prefix):
    if any(len(r.get("kinetic_energy_over_time", [])) > 2 for r in result["runs"]):
        time_series_plot(result["runs"], "kinetic_energy_over_time", "kinetic energy", prefix + "_kinetic.png")
    if result.get("pass_below") is not None and any(len(r.get("centroid_over_time", [])) > 2
                                                     for r in result["runs"]):
        # The ladder's pass test is on the lowest point, not the centroid: no line to pass here.
        centroid_plot(result["runs"], prefix + "_centroid.png")
    if result.get("accuracy") == "energy":
        energy_plot(result, prefix)
        return
    runs = [r for r in result["runs"] if "hausdorff_over_time" in r]
    fig, ax = plt.subplots(figsize=(6, 4))
    for r in runs:
        # The first frame is the shared initial state (distance zero up to round-off).
        frames = [(t, d) for t, d in r["hausdorff_over_time"] if t > 0]
        t, d = zip(*frames) if frames else ([], [])
        ax.plot(t, d, **ladder_line_style(r))
    ax.set_xlabel("time")
    ax.set_ylabel(f"Hausdorff distance to {result['reference']}")
    ax.set_yscale("log")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(prefix + "_hausdorff.png", dpi=110)
    plt.close(fig)

    measures = (("the run's own wall time [s]", run_seconds), ("vertices", lambda r: r["n_vertices"]))
    cost_figure(prefix + "_cost.png", runs, measures, lambda r: r["mean_hausdorff"], "mean Hausdorff distance",
                log_y=True)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("result")
    p.add_argument("--plots", help="directory for the PNGs (default: beside the JSON)")
    args = p.parse_args()
    with open(args.result) as f:
        result = json.load(f)
    plots(result, plot_prefix(args.result, args.plots))
    print(table(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
