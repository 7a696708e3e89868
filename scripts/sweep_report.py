#!/usr/bin/python3
"""The plot and the table of one sweep (scripts/sweep.py).

    scripts/sweep_report.py RESULT.json [--plot PATH.png]

Prints a Markdown table (every run: settings, vertices, time, accuracy, its time over that of a
fixed mesh of its accuracy interpolated between the rungs, on which front) and the knee's
verdict, and draws the runs' mean Hausdorff distance against their time on log-log axes:
the fixed rungs as a line labelled by their vertex counts, each r-ITR run as a point, r-ITR's
front as a line, its knee circled and the run of the best time to accuracy starred (default PATH: beside the JSON, NAME_pareto.png).
"""
import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def settings_text(run):
    return ", ".join(f"{k.split('/')[-1]} {v}" for k, v in run.get("settings", {}).items()) or "fixed mesh"


def table(result):
    until = result.get("accuracy_until")
    window = f", t <= {until:g}" if until is not None else ""
    lines = [f"| run | settings | vertices | time [s] | mean Hausdorff{window} | time / fixed mesh of its accuracy | front |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for r in result["runs"]:
        if r["name"] == result["reference"]:
            accuracy = "reference"
        else:
            accuracy = f"{r['mean_hausdorff']:.3g}" if "mean_hausdorff" in r else f"- (exit {r['exit_code']})"
        mark = "all" if r["name"] in result["front"] else ("r-ITR" if r["name"] in result["ritr_front"] else "")
        if r["name"] == result["knee"]:
            mark += " (knee)"
        if r["name"] == result.get("best"):
            mark += " (best time to accuracy)"
        ratio = (r.get("time_to_accuracy") or {}).get("interpolated_ratio")
        lines.append(f"| {r['name']} | {settings_text(r)} | {r.get('n_vertices', 0):,} | {r['seconds']:.2f} "
                     f"| {accuracy} | {f'{ratio:.2f}' if ratio else '-'} | {mark} |")
    if result.get("knee_verdict"):
        lines += ["", f"Knee of r-ITR's front, `{result['knee']}`: {result['knee_verdict']['sentence']}"]
    if result.get("best_verdict"):
        lines += ["", f"Best time to accuracy, `{result['best']}`: {result['best_verdict']['sentence']}"]
    return "\n".join(lines)


def plot(result, path):
    runs = {r["name"]: r for r in result["runs"] if "mean_hausdorff" in r}
    fixed = sorted((r for r in runs.values() if not r["adaptivity"]), key=lambda r: r["seconds"])
    ritr = [r for r in runs.values() if r["adaptivity"]]
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    ax.plot([r["seconds"] for r in fixed], [r["mean_hausdorff"] for r in fixed], "s-", color="0.35",
            label="fixed meshes")
    for r in fixed:
        ax.annotate(f"{r['n_vertices']:,}", (r["seconds"], r["mean_hausdorff"]), textcoords="offset points",
                    xytext=(5, 4), fontsize=8, color="0.35")
    hessians = sorted({r["settings"].get("Adaptivity/hessian", "") for r in ritr})
    for hessian, marker in zip(hessians, "o^vD"):
        group = [r for r in ritr if r["settings"].get("Adaptivity/hessian", "") == hessian]
        ax.plot([r["seconds"] for r in group], [r["mean_hausdorff"] for r in group], marker, alpha=0.6, linestyle="none",
                label=f"r-ITR {hessian}".strip())
    ritr_front = [runs[n] for n in result["ritr_front"]]
    ax.plot([r["seconds"] for r in ritr_front], [r["mean_hausdorff"] for r in ritr_front], "-", color="C3",
            label="r-ITR's front")
    if result.get("knee") in runs:
        k = runs[result["knee"]]
        ax.plot([k["seconds"]], [k["mean_hausdorff"]], "o", markersize=14, markerfacecolor="none", color="C3",
                label=f"knee: {settings_text(k)}")
    if result.get("best") in runs:
        b = runs[result["best"]]
        ax.plot([b["seconds"]], [b["mean_hausdorff"]], "*", markersize=16, markerfacecolor="none", color="C2",
                label=f"best time to accuracy: {settings_text(b)}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the run [s]")
    until = result.get("accuracy_until")
    ax.set_ylabel(f"mean Hausdorff distance to {result['reference']}" + (f", t <= {until:g}" if until is not None else ""))
    ax.set_title(os.path.splitext(os.path.basename(result["scene"]))[0].replace("_", " "))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("result")
    p.add_argument("--plot")
    args = p.parse_args()
    with open(args.result) as f:
        result = json.load(f)
    print(table(result))
    plot(result, args.plot or os.path.splitext(args.result)[0] + "_pareto.png")


if __name__ == "__main__":
    main()
