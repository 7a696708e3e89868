#!/usr/bin/python3
"""doc/benchmarks.md from the runs' results (doc/benchmarks/*.json) and its prose
(doc/benchmarks/report.md.in).

    scripts/benchmark_report.py            write doc/benchmarks.md (and draw missing plots)
    scripts/benchmark_report.py --plots    the same, redrawing every plot drawn from a JSON
    scripts/benchmark_report.py --check    exit 1 (one line naming the scene) if doc/benchmarks.md
                                           is not what this script writes

The template is Markdown in sections. `@section ID` starts a section of prose; `@scene NAME`
one backed by doc/benchmarks/NAME.json (scripts/ladder.py, scripts/friction_sweep.py or
scripts/sweep.py; written by the ctest paper_NAME). In a scene section:
- the text before `{{table}}` says what the scene is; when the JSON is missing, it is kept and
  the rest of the section becomes a note saying which ctest writes the JSON;
- `{{table}}` is the scene's table and its verdict, `{{plots()}}` the plots drawn from its JSON
  (NAME_hausdorff.png, NAME_cost.png, NAME_kinetic.png, NAME_energy.png, NAME_centroid.png,
  NAME_pareto.png), `{{reproduce}}` the command that measures it;
- `{{EXPRESSION}}` or `{{EXPRESSION|FORMAT}}` is a figure from the JSON: a Python expression over
  the names of `namespace()` below (e.g. `{{ritr.E|.2f}}`, `{{pct(ritr.E, finest.E)|%}}`); FORMAT
  is a format spec, `%` (a percentage: 1.6, 28, 0.02), `t` (seconds) or `n` (thousands);
- a line `% check EXPRESSION` is a claim of the prose that the JSON must bear out (else the
  script fails, naming the scene), any other line starting with `%` a comment.
`{{glance}}` (in any section) is the one-row-per-scene summary. Every image a section links must
exist; each scene's heading must give the anchor NAME with `_` as `-` (the README links them).
Tables give each run's own wall time (summary.json). Prose is wrapped again at 100 columns once
its figures are in. Both modes exit 1 on a claim that does not hold, a missing image or a wrong
anchor, one line each.
"""
import argparse
import json
import math
import os
import re
import statistics
import sys
import textwrap

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from accuracy_front import fixed_time_at, verdict  # noqa: E402
from ladder import further_than_every_rung, is_ritr, run_seconds  # noqa: E402

ROOT = os.path.normpath(os.path.join(HERE, ".."))
DOC = os.path.join(ROOT, "doc", "benchmarks.md")
RESULTS = os.path.join(ROOT, "doc", "benchmarks")
TEMPLATE = os.path.join(RESULTS, "report.md.in")
MARK = "<!-- section: {} -->"
CORNER_ON_VERTEX = 1e-4  # a stroke corner within this of a mesh vertex has a vertex on it


class ReportError(Exception):
    """A problem of one section: its message names the scene."""


# ---------------------------------------------------------------------------------------------
# Formatting


def percent(x):
    x = abs(x)
    return f"{x:.0f}" if x >= 10 else f"{x:.1f}" if x >= 1 else f"{x:.1g}"


def seconds_text(t):
    return f"{t:.2g}" if t < 1 else f"{t:.2f}" if t < 10 else f"{t:.1f}" if t < 100 else f"{t:,.0f}"


def fmt(value, spec=""):
    if spec == "%":
        return percent(value)
    if spec == "t":
        return seconds_text(value)
    if spec == "n":
        return f"{int(round(value)):,}"
    if spec:
        return format(value, spec)
    if isinstance(value, bool) or isinstance(value, str):
        return str(value)
    if isinstance(value, int):
        return f"{value:,}"
    if isinstance(value, float):
        return f"{value:.3g}"
    return str(value)


def slug(heading):
    """GitHub's anchor of a Markdown heading."""
    text = heading.lstrip("#").strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


# ---------------------------------------------------------------------------------------------
# Runs


class Run:
    """One run of a result, with short names for the figures the prose quotes."""

    def __init__(self, data, baseline):
        self.data = data
        self.name = data["name"]
        self.v = data.get("n_vertices", 0)
        self.t = run_seconds(data)
        self.mem = (data["peak_rss_bytes"] - baseline) / 2**20
        self.newton = data.get("total_newton_iterations")
        self.outer = data.get("total_outer_iterations")
        self.E = data.get("final_energy", math.nan)
        self.h = data.get("mean_hausdorff", math.nan)
        self.hmax = data.get("max_hausdorff", math.nan)
        self.low = data.get("lowest_point", math.nan)
        self.c = data.get("final_centroid", math.nan)
        self.passes = data.get("passes")
        self.mu = data.get("mu")
        self.exit = data["exit_code"]
        self.adaptive = is_ritr(data)

    def __repr__(self):
        return f"Run({self.name})"


def load(path):
    with open(path) as f:
        return json.load(f)


def kind(result):
    if "knee" in result:
        return "sweep"
    if "start" in result:
        return "branches"  # scripts/masticator_branches.py: runs started from r-ITR's frames
    if "mu" in result:
        return "friction"
    if result.get("accuracy") == "energy":
        return "energy"
    return "gap" if result.get("pass_below") is not None else "hausdorff"


def runs_of(result):
    base = result.get("baseline_rss_bytes", 0)
    return [Run(r, base) for r in result["runs"]]


def fixed_of(runs):
    return sorted((r for r in runs if not r.adaptive), key=lambda r: r.v)


def timed(run):
    return dict(run.data, seconds=run.t)


def accuracy_verdict(result, runs):
    """The time-to-accuracy verdict of the ladder's r-ITR run (scripts/accuracy_front.py)."""
    stored = (result.get("headline") or {}).get("time_to_accuracy")
    if stored:
        return stored
    candidates = [r for r in fixed_of(runs) if r.name != result["reference"] and r.exit == 0
                  and not math.isnan(r.h)]
    if not candidates or math.isnan(runs[0].h):
        return None
    return verdict(timed(runs[0]), [timed(r) for r in candidates])


def interpolated_ratio(run, runs, reference):
    """A run's time over that of a fixed mesh of its accuracy, interpolated between the rungs."""
    rungs = [timed(r) for r in fixed_of(runs) if r.name != reference and not math.isnan(r.h)]
    t = fixed_time_at(rungs, run.h) if rungs and not math.isnan(run.h) else None
    return run.t / t if t else None


# ---------------------------------------------------------------------------------------------
# Tables and verdicts


def row(cells):
    return "| " + " | ".join(cells) + " |"


def header(cells):
    return [row(cells), row(["---"] * len(cells))]


def cost_cells(r):
    return [f"{r.v:,}", seconds_text(r.t), f"{r.mem:,.0f}", fmt(r.newton), fmt(r.outer)]


def name_cell(r):
    return f"{r.name} (exit {r.exit})" if r.exit else r.name


COST = ["vertices", "time [s]", "memory [MiB]", "Newton its", "outer its"]


def hausdorff_table(result, runs):
    ref = result["reference"]
    until = result.get("accuracy_until")
    window = f", t <= {until:g}" if until is not None else ""
    lines = header(["run"] + COST + [f"mean Hausdorff{window}", f"max Hausdorff{window}", "time / fixed of its accuracy"])
    for r in runs:
        if r.name == ref:
            accuracy = ["reference", "reference"]
        elif math.isnan(r.h):
            accuracy = ["-", "-"]
        else:
            accuracy = [f"{r.h:.3g}", f"{r.hmax:.3g}"]
        ratio = interpolated_ratio(r, runs, ref) if r.adaptive else None
        lines.append(row([name_cell(r)] + cost_cells(r) + accuracy + [f"{ratio:.2f}" if ratio else "-"]))
    return lines


def corners_on_vertex(r):
    return sum(d <= CORNER_ON_VERTEX for d in r.data.get("corner_distances", []))


def energy_table(result, runs):
    gap = result.get("pass_below") is not None
    corners = result.get("corner_touch") is not None
    extra = (["lowest point", "outcome"] if gap else []) + (["corners on a vertex", "median corner distance"]
                                                            if corners else [])
    lines = header(["run"] + COST + ["final energy"] + extra)
    for r in runs:
        cells = [name_cell(r)] + cost_cells(r) + [f"{r.E:.6g}"]
        if gap:
            cells += [f"{r.low:.3f}", "passes" if r.passes else "locks"] if r.passes is not None else ["-", "-"]
        if corners:
            d = r.data.get("corner_distances", [])
            cells += [f"{corners_on_vertex(r)} of {len(d)}", f"{statistics.median(d):.1e}" if d else "-"]
        lines.append(row(cells))
    return lines


def gap_table(result, runs):
    """Each run's outcome and distance to the reference; with `ritr_distance` (scripts/ladder.py)
    also r-ITR's distance to each fixed rung: whether the ladder moves toward r-ITR."""
    to_ritr = any("ritr_distance" in r.data for r in runs)
    lines = header(["run"] + COST + ["lowest point", "outcome", f"mean Hausdorff to {result['reference']}"]
                   + (["r-ITR's distance to this rung"] if to_ritr else []))
    for r in runs:
        outcome = ("passes" if r.passes else "locks") if r.passes is not None else "-"
        low = f"{r.low:.3f}" if not math.isnan(r.low) else "-"
        cells = [name_cell(r)] + cost_cells(r) + [low, outcome, f"{r.h:.3g}" if not math.isnan(r.h) else "-"]
        if to_ritr:
            cells.append(f"{r.data['ritr_distance']:.3g}" if "ritr_distance" in r.data else "-")
        lines.append(row(cells))
    return lines


def friction_table(result, runs):
    lines = header(["run", "mu"] + COST + ["final centroid height", "outcome"])
    for r in runs:
        outcome = ("passes" if r.passes else "caught") if r.passes is not None else "-"
        centroid = f"{r.c:.3f}" if not math.isnan(r.c) else "-"
        lines.append(row([name_cell(r), f"{r.mu:g}"] + cost_cells(r) + [centroid, outcome]))
    return lines


def share(a, b):
    """a as a share of b, to go before "its time": "35 % of" or, from twice b on, "2.3x"."""
    return f"{a / b:.1f}x" if a >= 2 * b else f"{percent(100 * a / b)} % of"


def energy_verdict(result, runs):
    ritr, fixed = runs[0], [r for r in fixed_of(runs) if r.exit == 0]
    if ritr.exit != 0 or not fixed:
        return (result.get("headline") or {}).get("why", "no verdict") + "."
    match = next((r for r in fixed if r.E <= ritr.E), None)
    if match is None:
        finest = fixed[-1]
        return (f"r-ITR's final energy on {ritr.v:,} vertices is below every fixed rung's, the "
                f"{finest.v:,}-vertex mesh's included, in {share(ritr.t, finest.t)} its time.")
    return (f"The coarsest fixed mesh as low as r-ITR on {ritr.v:,} vertices has {match.v:,} vertices; "
            f"r-ITR takes {share(ritr.t, match.t)} its time.")


def gap_verdict(result, runs):
    ritr, fixed = runs[0], fixed_of(runs)
    passing = [r for r in fixed if r.passes]
    text = f"r-ITR on {ritr.v:,} vertices {'passes' if ritr.passes else 'locks'}; "
    if not passing:
        return text + f"every fixed rung locks, up to {fixed[-1].v:,} vertices."
    first = passing[0]
    text += f"the first fixed rung that passes has {first.v:,} vertices (r-ITR in {share(ritr.t, first.t)} its time)"
    if further_than_every_rung(result.get("headline") or {}):
        text += ", but by distance to the finest rung r-ITR is further than every coarser rung"
    return text + "."


def friction_verdict(result, runs):
    ritr = [r for r in runs if r.adaptive]
    same = [r for r in runs if not r.adaptive and r.data.get("refinements") == 0]

    def outcomes(group):
        by = {}
        for r in sorted(group, key=lambda r: r.mu):
            by.setdefault("passes" if r.passes else "is caught", []).append(f"{r.mu:g}")
        return " and ".join(f"{word} at mu {', '.join(mus)}" for word, mus in by.items())

    text = f"r-ITR on {ritr[0].v:,} vertices {outcomes(ritr)}; the fixed mesh of its size {outcomes(same)}."
    h = result.get("headline") or {}
    match = next((r for r in runs if r.name == h.get("matching_fixed")), None)
    if match is not None:
        text += (f" The first fixed rung that passes at mu {match.mu:g} has {match.v:,} vertices; r-ITR takes "
                 f"{share(ritr[0].t, match.t)} its time.")
    elif h.get("why"):
        text += f" {h['why'][0].upper()}{h['why'][1:]}."
    return text


def hausdorff_verdict(result, runs):
    v = accuracy_verdict(result, runs)
    head = result.get("headline") or {}
    if v and head.get("draws"):
        # scripts/ladder.py --draws: r-ITR judged by the mean over its run and perturbed repeats.
        d = head["draws"]
        repeats = f"`{d[1]}`" if len(d) == 2 else f"`{d[1]}` to `{d[-1]}`"
        return (f"Judged over {len(d)} draws (`{d[0]}` and {repeats}, mean {head['ritr_mean_hausdorff']:.4f}) "
                f"at the time of `{d[0]}`: {v['sentence']}")
    if v:
        return v["sentence"]
    return (result.get("headline") or {}).get("why", "no verdict") + "."


def verdict_of(result):
    k = kind(result)
    if k == "branches":
        return result["headline"]["sentence"]
    if k == "sweep":
        v = result.get("best_verdict")
        return (f"Best time to accuracy, `{result['best']}`: {v['sentence']}" if v else
                "No r-ITR run was measured against the ladder.")
    runs = runs_of(result)
    return {"energy": energy_verdict, "gap": gap_verdict, "friction": friction_verdict,
            "hausdorff": hausdorff_verdict}[k](result, runs)


def plot_names(name, result):
    """(file, caption) of the plots drawn from a result (scripts/ladder_report.py's rules)."""
    k = kind(result)
    if k == "branches":
        return []  # its section's table says it; the masticator's own plots show the branches
    if k == "sweep":
        return [(f"{name}_pareto.png", "mean Hausdorff distance against time, every run")]
    if k == "friction":
        return [(f"{name}_centroid.png", "centroid height over time")]
    out = []
    runs = result["runs"]
    if k != "energy":
        out += [(f"{name}_hausdorff.png", f"Hausdorff distance to {result['reference']} over time"),
                (f"{name}_cost.png", "mean Hausdorff distance against time and vertices")]
    if any(len(r.get("kinetic_energy_over_time", [])) > 2 for r in runs):
        out.append((f"{name}_kinetic.png", "kinetic energy over time"))
    if result.get("pass_below") is not None and any(len(r.get("centroid_over_time", [])) > 2 for r in runs):
        out.append((f"{name}_centroid.png", "centroid height over time"))
    if k == "energy":
        out.append((f"{name}_energy.png", "final energy against vertices, time and memory"))
    return out


def draw_plots(name, result, results_dir, redraw):
    """Draw the plots of a result that are missing (all of them with `redraw`)."""
    wanted = [os.path.join(results_dir, f) for f, _ in plot_names(name, result)]
    if not wanted or not redraw and all(os.path.exists(p) for p in wanted):
        return
    prefix = os.path.join(results_dir, name)
    k = kind(result)
    if k == "sweep":
        import sweep_report
        sweep_report.plot(result, prefix + "_pareto.png")
    elif k == "friction":
        import friction_sweep_report
        friction_sweep_report.plot(result, prefix + "_centroid.png")
    else:
        import ladder_report
        ladder_report.plots(result, prefix)


def scene_table(name, result):
    k = kind(result)
    if k == "sweep":
        import sweep_report
        lines = [sweep_report.table(result)]
    else:
        runs = runs_of(result)
        table = {"energy": energy_table, "gap": gap_table, "friction": friction_table,
                 "hausdorff": hausdorff_table}[k](result, runs)
        lines = ["\n".join(table), "", f"**Verdict.** {verdict_of(result)}"]
    return "\n".join(lines)


def plot_links(name, result):
    return " ".join(f"![{caption}](benchmarks/{f})" for f, caption in plot_names(name, result))


def reproduce(name, result):
    # A resumed run's process time is its last part's; its own summed time counts every part. A
    # short run timed as the fastest of several (--timing-repeats) ran that many times.
    minutes = sum(max(r.get("wall_seconds", 0), run_seconds(r)) * r.get("timing_repeats", 1) for r in result["runs"]) / 60
    length = f"about {minutes:.0f} minutes" if minutes >= 1.5 else "about a minute"
    return (f"Reproduce: `ctest -R '^paper_{name}$'` in `build/` ({length}), then "
            "`scripts/benchmark_report.py --plots`.")


# ---------------------------------------------------------------------------------------------
# The prose's figures


def namespace(name, result):
    """The names a placeholder or a check of a scene section may use."""
    runs = runs_of(result) if kind(result) != "sweep" else []
    by_name = {r.name: r for r in runs}
    fixed = fixed_of(runs)

    def run(name):
        if name not in by_name:
            raise ReportError(f"no run {name} in the result")
        return by_name[name]

    def pct(a, b):
        return 100 * abs(a - b) / abs(b)

    def rel(a, b, lower, higher):
        """a against b in words: '12 % lower', '2.5x higher' (with the words given; a factor once
        one is twice the other)."""
        word = lower if a < b else higher
        if max(abs(a), abs(b)) >= 2 * min(abs(a), abs(b)):
            return f"{max(abs(a), abs(b)) / min(abs(a), abs(b)):.1f}x {word}"
        return f"{percent(pct(a, b))} % {word}"

    def times(a, b, lower, higher):
        """'2.3x lower' or '2.3x higher' (with the words given): the factor between a and b."""
        return f"{max(a, b) / min(a, b):.1f}x {lower if a < b else higher}"

    def values(items, attribute, spec=""):
        return ", ".join(fmt(getattr(r, attribute), spec) for r in items)

    def differences(items, attribute, spec=".0f"):
        v = [getattr(r, attribute) for r in items]
        return ", ".join(fmt(abs(a - b), spec) for a, b in zip(v, v[1:]))

    def phase(r, t0, t1, series="hausdorff_over_time"):
        d = [x for t, x in r.data.get(series, []) if t0 < t <= t1]
        return sum(d) / len(d) if d else math.nan

    def source_phase(r, t0, t1):
        """A restarted run's mean distance to the run it started from (masticator_branches)."""
        return phase(r, t0, t1, "source_hausdorff_over_time")

    def kinetic_peak(r, t0, t1):
        return max((x for t, x in r.data.get("kinetic_energy_over_time", []) if t0 < t <= t1), default=math.nan)

    def kinetic_gap(r, reference):
        """The largest difference of two runs' kinetic energies over their common frames, in % of
        the reference's initial kinetic energy."""
        mine = dict(map(tuple, r.data.get("kinetic_energy_over_time", [])))
        theirs = reference.data.get("kinetic_energy_over_time", [])
        return 100 * max(abs(mine[t] - k) for t, k in theirs if t in mine) / theirs[0][1]

    def phase_table(bounds):
        """Mean Hausdorff distance and peak kinetic energy of every run between the times `bounds`."""
        edges = [0] + list(bounds) + [math.inf]
        spans = [f"t <= {edges[1]:g}"] + [f"{a:g} < t <= {b:g}" for a, b in zip(edges[1:-2], edges[2:-1])] \
            + [f"t > {edges[-2]:g}"]
        lines = header(["run", "vertices"] + [f"distance, {s}" for s in spans]
                       + [f"peak kinetic energy [J], {s}" for s in spans])
        for r in runs:
            # "-": no frame in the span (a run started later, masticator_branches).
            distances = [("-" if math.isnan(phase(r, a, b)) else fmt(phase(r, a, b), ".3g"))
                         if r.name != result["reference"] else "reference" for a, b in zip(edges, edges[1:])]
            peaks = ["-" if math.isnan(kinetic_peak(r, a, b)) else fmt(kinetic_peak(r, a, b), ".0f")
                     for a, b in zip(edges, edges[1:])]
            lines.append(row([r.name, f"{r.v:,}"] + distances + peaks))
        return "\n".join(lines)

    def runs_like(prefix):
        """The runs whose names start with `prefix`, in the result's order."""
        return [r for r in runs if r.name.startswith(prefix)]

    def mean(values):
        values = list(values)
        return sum(values) / len(values) if values else math.nan

    def end_drop(r, side, below=-0.5):
        """The first frame time at which a run's left (side 0) or right (1) end is below height
        `below` (ladder.py --end-heights); nan if it never is."""
        return next((f[0] for f in r.data.get("end_heights_over_time", []) if f[1 + side] < below), math.nan)

    def end_table(names, at):
        """The heights of the named runs' left / right ends at the frame times `at`."""
        lines = header(["run", "vertices"] + [f"t = {t:g}" for t in at])
        for name in names:
            heights = {round(f[0], 6): f[1:] for f in run(name).data.get("end_heights_over_time", [])}
            cells = [" / ".join(fmt(y, "+.2f") for y in heights[round(t, 6)]) if round(t, 6) in heights else "-"
                     for t in at]
            lines.append(row([name, f"{run(name).v:,}"] + cells))
        return "\n".join(lines)

    def sweep_run(run_name):
        """A run of a sweep, as its JSON has it."""
        found = [r for r in result.get("runs", []) if r["name"] == run_name]
        if not found:
            raise ReportError(f"no run {run_name} in the result")
        return found[0]

    def sweep_mean(run_name, until=math.inf):
        """A sweep run's mean Hausdorff distance over its frames up to `until` (every frame by
        default: the whole run, whatever window ranks the sweep)."""
        d = [x for t, x in sweep_run(run_name).get("hausdorff_over_time", []) if t <= until]
        return sum(d) / len(d) if d else math.nan

    h = result.get("headline") or {}
    same = [r for r in fixed if r.v == runs[0].v] if runs else []
    return dict(
        result=result, runs=runs, run=run, fixed=fixed, ritr=runs[0] if runs else None,
        same=same[0] if same else (fixed[0] if fixed else None),
        finest=fixed[-1] if fixed else None, match=by_name.get(h.get("matching_fixed") or ""),
        pct=pct, rel=rel, times=times, share=share, values=values, differences=differences,
        phase=phase, source_phase=source_phase, kinetic_peak=kinetic_peak, kinetic_gap=kinetic_gap, phase_table=phase_table,
        front_ratio=lambda r: interpolated_ratio(r, runs, result.get("reference")),
        corners=corners_on_vertex, verdict=lambda: verdict_of(result), plots=lambda: plot_links(name, result),
        sweep_run=sweep_run, sweep_mean=sweep_mean, end_drop=end_drop, end_table=end_table,
        runs_like=runs_like, mean=mean,
        abs=abs, min=min, max=max, len=len, sum=sum, all=all, any=any, sorted=sorted, round=round, zip=zip, dict=dict)


PLACEHOLDER = re.compile(r"\{\{(.+?)\}\}")


def evaluate(expression, names):
    """An expression of the template (the project's own text) over the names of a scene; the
    names are globals, so that comprehensions see them too."""
    return eval(expression, {"__builtins__": {}, **names})


def fill(text, names, where):
    def one(match):
        expression, _, spec = match.group(1).strip().partition("|")
        try:
            value = evaluate(expression, names)
        except ReportError as e:
            raise ReportError(f"{where}: {{{{{match.group(1)}}}}}: {e}")
        except Exception as e:  # noqa: BLE001 - any error of the prose's expression names it
            raise ReportError(f"{where}: {{{{{match.group(1)}}}}}: {type(e).__name__}: {e}")
        return fmt(value, spec.strip())
    return PLACEHOLDER.sub(one, text)


# ---------------------------------------------------------------------------------------------
# The document


def parse(template_text):
    """[(kind, id, [(line number, line), ...])] of the template's sections."""
    sections = []
    for number, line in enumerate(template_text.splitlines(), 1):
        m = re.match(r"@(section|scene) +(\S+) *$", line)
        if m:
            sections.append((m.group(1), m.group(2), []))
        elif sections:
            sections[-1][2].append((number, line))
        elif line.strip() and not line.startswith("%"):
            raise ReportError(f"template line {number}: text before the first @section or @scene")
    return sections


def first_sentence(text):
    head, dot, _ = text.partition(". ")
    return head + "." if dot else text


def heading_of(lines):
    return next((line for _, line in lines if line.startswith("#")), None)


class Block(str):
    """Generated text (a table) that the prose's wrapping leaves alone."""


class Document:
    def __init__(self, template, results_dir):
        self.template, self.results_dir = template, results_dir
        with open(template) as f:
            self.sections = parse(f.read())
        self.results = {}
        for kind_, ident, _ in self.sections:
            path = os.path.join(results_dir, ident + ".json")
            if kind_ == "scene" and os.path.exists(path):
                self.results[ident] = load(path)

    def glance(self):
        lines = header(["scene", "r-ITR", "against the fixed meshes"])
        for kind_, ident, body in self.sections:
            if kind_ != "scene":
                continue
            title = heading_of(body).lstrip("#").strip()
            link = f"[{title}](#{slug(heading_of(body))})"
            result = self.results.get(ident)
            if result is None:
                lines.append(row([link, "-", f"not measured yet (`ctest -R '^paper_{ident}$'`)"]))
                continue
            if kind(result) == "sweep":
                runs = [r for r in result["runs"] if r.get("adaptivity")]
                lines.append(row([link, f"{len(runs)} settings", verdict_of(result)]))
                continue
            if kind(result) == "branches":
                lines.append(row([link, f"restarts at t = {result['start']:g}", verdict_of(result)]))
                continue
            ritr = runs_of(result)[0]
            figure = {"energy": f"energy {ritr.E:.6g}", "hausdorff": f"Hausdorff {ritr.h:.3g}",
                      "gap": "passes" if ritr.passes else "locks",
                      "friction": f"centroid {ritr.c:.3f}"}[kind(result)]
            # Dynamics: the sentence of time to accuracy whole (r-ITR on the fixed ladder's front
            # or not is its second half).
            verdict = verdict_of(result) if kind(result) == "hausdorff" else first_sentence(verdict_of(result))
            lines.append(row([link, f"{ritr.v:,} vertices, {figure}, {seconds_text(ritr.t)} s", verdict]))
        return "\n".join(lines)

    def render_section(self, kind_, ident, body):
        where = f"{ident}" + (f" (doc/benchmarks/{ident}.json)" if kind_ == "scene" else "")
        result = self.results.get(ident)
        names = namespace(ident, result) if result is not None else {}
        out, problems = [], []
        for number, line in body:
            if line.startswith("%"):
                m = re.match(r"% *check +(.+)$", line)
                if m and result is not None:
                    try:
                        ok = evaluate(m.group(1), names)
                    except Exception as e:  # noqa: BLE001
                        raise ReportError(f"{where}: check on template line {number}: {type(e).__name__}: {e}")
                    if not ok:
                        problems.append(f"{where}: the prose's claim `{m.group(1)}` (template line {number}) "
                                        "does not hold for the results")
                continue
            stripped = line.strip()
            if kind_ == "scene" and result is None and stripped in ("{{table}}", "{{reproduce}}"):
                out += [f"> Not measured yet: `doc/benchmarks/{ident}.json` is missing. `ctest -R '^paper_{ident}$'` "
                        "from `build/` writes it; then run `scripts/benchmark_report.py --plots`."]
                break
            if stripped == "{{glance}}":
                out.append(Block(self.glance()))
            elif stripped == "{{table}}":
                out.append(Block(scene_table(ident, result)))
            elif stripped == "{{reproduce}}":
                out.append(reproduce(ident, result))
            elif "{{" in line:
                if result is None:
                    raise ReportError(f"{where}: template line {number}: a figure outside a scene with results")
                out.append(fill(line, names, f"{where}, template line {number}"))
            else:
                out.append(line)
        while out and not out[-1].strip():
            out.pop()
        # The prose is wrapped again (its figures change the lines' lengths); tables stay as printed.
        pieces, prose = [], []
        for item in out + [Block("")]:
            if isinstance(item, Block):
                if prose:
                    pieces.append(rewrap("\n".join(prose)))
                    prose = []
                pieces.append(str(item))
            else:
                prose.append(item)
        text = "\n".join(pieces[:-1])
        for target in re.findall(r"\]\((benchmarks/[^)\s]+)\)", text):
            if not os.path.exists(os.path.join(self.results_dir, target.split("/", 1)[1])):
                problems.append(f"{where}: links {target}, which does not exist")
        if kind_ == "scene" and not ident.endswith("_sweep"):
            heading = heading_of(body)
            if heading is None or slug(heading) != ident.replace("_", "-"):
                problems.append(f"{where}: its heading {heading!r} does not give the anchor #{ident.replace('_', '-')}")
        return text, problems

    def render(self):
        """(the document, its sections as {id: text}, the problems found)."""
        parts, by_id, problems = [], {}, []
        for kind_, ident, body in self.sections:
            text, found = self.render_section(kind_, ident, body)
            problems += found
            by_id[ident] = text
            parts.append(MARK.format(ident) + "\n" + text)
        document = "\n\n".join(parts) + "\n"
        slugs = [slug(line) for line in document.splitlines() if re.match(r"#+ ", line)]
        duplicated = sorted({s for s in slugs if slugs.count(s) > 1})
        if duplicated:
            problems.append("headings give the same anchor twice: " + ", ".join(duplicated))
        return document, by_id, problems

    def draw(self, redraw):
        for ident, result in self.results.items():
            draw_plots(ident, result, self.results_dir, redraw)


WIDTH = 100


def rewrap(text):
    """Paragraphs of plain text wrapped again at WIDTH, so that filled-in figures leave no ragged
    lines; tables, lists, images, headings, comments and quotes stay as they are."""
    out, paragraph = [], []

    def flush():
        if paragraph:
            lines = textwrap.wrap(" ".join(paragraph), WIDTH, break_long_words=False, break_on_hyphens=False)
            for i in range(1, len(lines)):
                # A line may not start what Markdown would read as a block of its own.
                while re.match(r"([>#|]|[-+*] )", lines[i]) and " " in lines[i - 1]:
                    head, word = lines[i - 1].rsplit(" ", 1)
                    lines[i - 1], lines[i] = head, word + " " + lines[i]
            out.extend(lines)
            paragraph.clear()

    for line in text.split("\n"):
        if not line.strip():
            flush()
            out.append(line)
        elif re.match(r"\s*([|#>]|[-+*] |!\[|<!--|\d+\. )", line) or (paragraph == [] and line.startswith(" ")):
            flush()
            out.append(line)
        elif out and re.match(r"\s*- ", out[-1]) and line.startswith("  ") and not paragraph:
            out.append(line)  # a list item's continuation
        else:
            paragraph.append(line.strip())
    flush()
    return "\n".join(out)


def split(document):
    """{id: text} of a generated document's sections."""
    out, current, lines = {}, None, []
    for line in document.splitlines():
        m = re.match(r"<!-- section: (\S+) -->$", line)
        if m:
            if current is not None:
                out[current] = "\n".join(lines).strip("\n")
            current, lines = m.group(1), []
        elif current is not None:
            lines.append(line)
    if current is not None:
        out[current] = "\n".join(lines).strip("\n")
    return out


def first_difference(expected, actual, scenes):
    """The section to name where a written document differs from the expected one: the first
    differing scene backed by a result (the summary at the top differs with it), else the first
    differing section."""
    want, have = split(expected), split(actual)
    differing = [i for i, text in want.items() if have.get(i) != text.strip("\n")]
    differing += [i for i in have if i not in want]
    backed = [i for i in differing if i in scenes]
    return (backed or differing or ["the document's layout"])[0]


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--check", action="store_true", help="exit 1 if the document is not the one this writes")
    p.add_argument("--plots", action="store_true", help="redraw every plot drawn from a JSON")
    p.add_argument("--template", default=TEMPLATE)
    p.add_argument("--results", default=RESULTS, help="the JSONs' and plots' folder (the document links it as benchmarks/)")
    p.add_argument("--out", default=DOC)
    args = p.parse_args(argv)
    try:
        document = Document(args.template, args.results)
        if not args.check:
            document.draw(args.plots)
        text, _, problems = document.render()
    except ReportError as e:
        print(f"benchmark_report: {e}", file=sys.stderr)
        return 1
    if args.check:
        try:
            with open(args.out) as f:
                written = f.read()
        except OSError:
            written = ""
        if written != text:
            ident = first_difference(text, written, document.results)
            source = f"doc/benchmarks/{ident}.json" if ident in document.results else "doc/benchmarks/report.md.in"
            print(f"benchmark_report: {os.path.relpath(args.out, ROOT)} differs from {source} in section {ident} "
                  "(run scripts/benchmark_report.py)", file=sys.stderr)
            return 1
    else:
        with open(args.out, "w") as f:
            f.write(text)
    for problem in problems:
        print(f"benchmark_report: {problem}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
