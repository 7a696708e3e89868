#!/usr/bin/python3
"""A Markdown table and the plot of one friction sweep (scripts/friction_sweep.py).

    scripts/friction_sweep_report.py RESULT.json [--plots DIR]

Prints the table to stdout and writes NAME_centroid.png beside the JSON (or into DIR): the
height of each run's centroid over time, r-ITR per friction coefficient in bold lines, the
fixed mesh of its size dashed and the finer fixed rungs thin (the paper's Fig. 21).
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ladder_report import centroid_plot, cost_cells, cost_ratio_text, plot_prefix  # noqa: E402


def table(result):
    base = result["baseline_rss_bytes"]
    lines = ["| run | mu | vertices | wall [s] | peak RSS - baseline [MiB] | Newton its | outer its "
             "| final centroid height | outcome | exit |",
             "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"]
    for r in result["runs"]:
        outcome = ("passes" if r["passes"] else "caught") if "passes" in r else "-"
        centroid = f"{r['final_centroid']:.3f}" if "final_centroid" in r else "-"
        lines.append(f"| {r['name']} | {r['mu']:g} | {cost_cells(r, base)} | {centroid} | {outcome} | {r['exit_code']} |")
    lines += ["", f"A run passes when its centroid ends below y = {result['pass_below']:g}."]
    h = result["headline"]
    if not h.get("matching_fixed"):
        lines.append(f"No headline: {h['why']}.")
    else:
        lines.append(f"Headline: `{h['matching_fixed']}` ({h['why']}): {h['vertex_ratio']:.1f}x r-ITR's vertices, "
                     f"{cost_ratio_text(h, base)}.")
    for line in result.get("unexpected", []):
        lines.append(f"Unexpected: {line}.")
    return "\n".join(lines)


def plot(result, path):
    colours = dict(zip(result["mu"], ("tab:green", "tab:blue", "tab:red", "tab:purple")))

    def style(r):
        label = f"{r['name']} ({r.get('n_vertices', '?')} v)"
        if r["adaptivity"]:
            return dict(color=colours.get(r["mu"]), linewidth=2.5, label=label)
        if r["refinements"] == 0:
            return dict(color=colours.get(r["mu"]), linewidth=1.5, linestyle="--", label=label)
        return dict(color="grey", linewidth=0.8, alpha=0.4 + 0.15 * r["refinements"], label=label)

    centroid_plot(result["runs"], path, style, pass_below=result["pass_below"])


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("result")
    p.add_argument("--plots", help="directory for the PNG (default: beside the JSON)")
    args = p.parse_args()
    with open(args.result) as f:
        result = json.load(f)
    plot(result, plot_prefix(args.result, args.plots) + "_centroid.png")
    print(table(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
