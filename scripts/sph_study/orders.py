"""Numbers: observed order and the speed-accuracy (Pareto) comparison. Pure functions (--self-test)."""

import math


def observed_order(e1, e2, h1, h2):
    """Observed convergence order between two resolutions: log(e1/e2) / log(h1/h2); None if undefined."""
    try:
        e1, e2, h1, h2 = float(e1), float(e2), float(h1), float(h2)
    except (TypeError, ValueError):
        return None
    if not all(math.isfinite(v) and v > 0 for v in (e1, e2, h1, h2)) or h1 == h2:
        return None
    return math.log(e1 / e2) / math.log(h1 / h2)


def time_to_reach(points, level):
    """Wall time a line needs to reach error <= level.

    points: [(wall_time, error)] in order of increasing resolution. Between two successive runs that
    bracket the level, the time is interpolated linearly in log(time)-log(error) (exact for power laws).
    Returns (time, exact) where exact is False when the coarsest run is already below the level (the
    time is then an upper bound), or (None, False) when no run reaches the level."""
    pts = [(t, e) for t, e in points if t and e and t > 0 and e > 0 and math.isfinite(t) and math.isfinite(e)]
    if not pts:
        return None, False
    if pts[0][1] <= level:
        return pts[0][0], False
    for (t1, e1), (t2, e2) in zip(pts, pts[1:]):
        if e1 > level >= e2:
            frac = math.log(e1 / level) / math.log(e1 / e2)
            return math.exp(math.log(t1) + frac * (math.log(t2) - math.log(t1))), True
    return None, False


def nice_levels(lo, hi, max_levels=8):
    """Error levels 1, 2, 5 x 10^k in [lo, hi] (decades only when there are too many; finer round
    numbers, then 5 geometrically spaced 2-digit values, when the range is too narrow for 3)."""
    if not (lo > 0 and hi >= lo):
        return []

    def between(mantissas):
        out = []
        for k in range(math.floor(math.log10(lo)) - 1, math.ceil(math.log10(hi)) + 1):
            for m in mantissas:
                v = float("%.12g" % (m * 10.0 ** k))
                if lo * (1 - 1e-12) <= v <= hi * (1 + 1e-12):
                    out.append(v)
        return out

    levels = between((1, 2, 5))
    if len(levels) > max_levels:
        decades = [v for v in levels if abs(math.log10(v) - round(math.log10(v))) < 1e-9]
        levels = decades if len(decades) >= 2 else levels[::max(1, len(levels) // max_levels)]
    if len(levels) < 3:
        levels = between((1, 1.5, 2, 3, 4, 5, 6, 7, 8, 9))
    if len(levels) < 3 and hi > lo:
        def round2(v, how):  # to 2 significant digits: up, down or nearest
            e = 10.0 ** (math.floor(math.log10(v)) - 1)
            q = v / e
            q = math.ceil(q - 1e-9) if how == "up" else math.floor(q + 1e-9) if how == "down" else round(q)
            return float("%.12g" % (q * e))
        levels = [round2(lo * (hi / lo) ** (k / 4.0), "up" if k == 0 else "down" if k == 4 else "nearest")
                  for k in range(5)]
        levels = [v for v in levels if lo * (1 - 1e-12) <= v <= hi * (1 + 1e-12)] or levels
    if len(levels) > max_levels:
        levels = levels[::math.ceil(len(levels) / max_levels)]
    return sorted(set(levels), reverse=True)


def pareto_table(lines, levels=None):
    """For each error level, the wall time every line needs to reach it and the fastest line.

    lines: {label: [(wall_time, error), ...] by increasing resolution}. Levels default to the 1-2-5
    values between the smallest error of any line and the largest coarsest-run error (so that at least
    one line has to refine to reach each level). Returns [{level, times: {label: (t, exact)}, best,
    runner_up, speedup}]."""
    lines = {k: [(t, e) for t, e in v if t and e and t > 0 and e > 0] for k, v in lines.items()}
    lines = {k: v for k, v in lines.items() if v}
    if not lines:
        return []
    if levels is None:
        lo = min(e for v in lines.values() for _, e in v)
        hi = max(v[0][1] for v in lines.values())
        levels = nice_levels(lo, hi)
    rows = []
    for level in levels:
        times = {k: time_to_reach(v, level) for k, v in lines.items()}
        reached = sorted((t, k) for k, (t, _) in times.items() if t is not None)
        best = reached[0][1] if reached else None
        runner = reached[1][1] if len(reached) > 1 else None
        speedup = reached[1][0] / reached[0][0] if len(reached) > 1 else None
        rows.append({"level": level, "times": times, "best": best, "runner_up": runner, "speedup": speedup})
    return rows
