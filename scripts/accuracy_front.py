"""Time to accuracy: which runs are worth their time, and the one-sentence verdict on r-ITR.

A run is a dict with an error (`mean_hausdorff`, lower is better) and a time (`seconds`).
A run is on the front of a set when no other run of the set is at least as accurate in at most
its time (and strictly better in one of the two). The fixed ladder's time at a given error is
interpolated between its rungs on log-log axes, so that an r-ITR run between two rungs can be
compared with what a fixed mesh of that accuracy would cost.
"""
import math


def dominates(a, b):
    """Whether run a is at least as accurate as b in at most its time, and better in one."""
    return (a["mean_hausdorff"] <= b["mean_hausdorff"] and a["seconds"] <= b["seconds"]
            and (a["mean_hausdorff"] < b["mean_hausdorff"] or a["seconds"] < b["seconds"]))


def front(runs):
    """The runs no other run dominates, fastest first."""
    return sorted((r for r in runs if not any(dominates(o, r) for o in runs if o is not r)),
                  key=lambda r: r["seconds"])


def knee(runs):
    """The knee of a front: on log-log axes, the point farthest below the chord joining its
    fastest and its most accurate end (the first of the ends for fronts of one or two runs)."""
    points = front(runs)
    if len(points) <= 2:
        return points[0] if points else None
    xy = [(math.log(r["seconds"]), math.log(r["mean_hausdorff"])) for r in points]
    (x0, y0), (x1, y1) = xy[0], xy[-1]
    length = math.hypot(x1 - x0, y1 - y0)
    distance = [((x1 - x0) * (y0 - y) - (x0 - x) * (y1 - y0)) / length for x, y in xy]
    return points[max(range(len(points)), key=lambda i: distance[i])]


def fixed_time_at(fixed, error):
    """The time a fixed mesh of the given error would take: log-log interpolation between the
    two rungs whose errors bracket it (None outside the ladder's range)."""
    rungs = sorted(fixed, key=lambda r: r["mean_hausdorff"], reverse=True)
    for coarse, fine in zip(rungs, rungs[1:]):
        e0, e1 = coarse["mean_hausdorff"], fine["mean_hausdorff"]
        if e1 <= error <= e0 and e0 > e1:
            w = math.log(e0 / error) / math.log(e0 / e1)
            return math.exp((1 - w) * math.log(coarse["seconds"]) + w * math.log(fine["seconds"]))
    return None


def verdict(ritr, fixed):
    """{sentence, on_front, matched, time_ratio, interpolated_ratio} of one r-ITR run against the
    fixed rungs (each with `n_vertices`): the finest rung r-ITR is at least as accurate as and
    r-ITR's time over that rung's; r-ITR's time over that of a fixed mesh of its accuracy,
    interpolated between the rungs; and whether it is on the front, i.e. below that interpolated
    ladder (or more accurate than every rung and faster than the finest)."""
    rungs = sorted(fixed, key=lambda r: r["n_vertices"])
    beaten = [r for r in rungs if ritr["mean_hausdorff"] <= r["mean_hausdorff"]]
    interpolated = fixed_time_at(rungs, ritr["mean_hausdorff"])
    result = {"matched": None, "time_ratio": None,
              "interpolated_ratio": ritr["seconds"] / interpolated if interpolated else None}
    if not beaten:
        result["on_front"] = False
        result["sentence"] = (f"r-ITR does not reach the accuracy of any fixed rung: its mean Hausdorff distance "
                              f"{ritr['mean_hausdorff']:.3g} is above the {rungs[0]['n_vertices']:,}-vertex mesh's "
                              f"{rungs[0]['mean_hausdorff']:.3g}.")
        return result
    matched = beaten[-1]
    ratio = ritr["seconds"] / matched["seconds"]
    result.update(matched=matched["name"], time_ratio=ratio)
    if ratio <= 1:
        sentence = (f"r-ITR reaches the accuracy of the {matched['n_vertices']:,}-vertex fixed mesh in "
                    f"{100 * ratio:.0f} % of its time.")
    else:
        sentence = (f"r-ITR reaches the accuracy of the {matched['n_vertices']:,}-vertex fixed mesh but not in less "
                    f"time: it takes {100 * ratio:.0f} % of that mesh's time.")
    if interpolated:
        result["on_front"] = ritr["seconds"] < interpolated
        sentence += (f" A fixed mesh of r-ITR's accuracy, interpolated between the rungs, would take "
                     f"{100 * interpolated / ritr['seconds']:.0f} % of r-ITR's time, so r-ITR is "
                     f"{'on' if result['on_front'] else 'not on'} the front.")
    else:
        # More accurate than every rung: on the front unless the finest rung is also faster.
        result["on_front"] = ratio <= 1
        sentence += f" It is more accurate than every rung{'' if ratio <= 1 else ', but slower than the finest'}."
    result["sentence"] = sentence
    return result
