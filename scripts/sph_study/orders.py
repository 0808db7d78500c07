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


def three_grid_order(h, f):
    """Observed order of a quantity with no exact value from three resolutions: h = (h1, h2, h3) fine to
    coarse, f their values. Solves p ln r21 = ln(e32/e21) + ln((r21^p - s)/(r32^p - s)), e32 = f3 - f2,
    e21 = f2 - f1, s = sign(e32/e21), r21 = h2/h1, r32 = h3/h2 (Celik et al. 2008, Roache's GCI), which
    is exact for f = f0 + C h^p. Returns (p, s), or (None, s) when undefined (equal values, equal h, no
    converging solution); p < 0 when the differences grow with refinement."""
    try:
        (h1, h2, h3), (f1, f2, f3) = [float(v) for v in h], [float(v) for v in f]
    except (TypeError, ValueError):
        return None, 0
    if not all(math.isfinite(v) for v in (h1, h2, h3, f1, f2, f3)) or not 0 < h1 < h2 < h3:
        return None, 0
    e21, e32 = f2 - f1, f3 - f2
    if e21 == 0 or e32 == 0:
        return None, 0
    s = 1 if e32 / e21 > 0 else -1
    r21, r32 = h2 / h1, h3 / h2
    base = math.log(abs(e32 / e21))
    p = base / math.log(r21)
    for _ in range(200):  # fixed point; one step when r21 == r32 (then q = 0)
        try:
            q = math.log((r21 ** p - s) / (r32 ** p - s))
        except (ValueError, ZeroDivisionError, OverflowError):
            return None, s
        new = (base + q) / math.log(r21)
        if abs(new - p) <= 1e-15 * max(1.0, abs(new)):
            return new, s
        p = new
    return None, s


def richardson(h, f, assumed_order=None):
    """Richardson extrapolation of a quantity to h -> 0 with the uncertainty of Roache's grid convergence
    index. h, f: the resolutions' h and values (any order). With three or more resolutions the finest three
    give the observed order p and the factor of safety is 1.25; with two, p is assumed_order and the
    factor is 3. Returns {value, uncertainty (absolute, Fs |f1 - f2| / (r21^p - 1)), gci (relative to the
    finest value, None if it is 0), order, observed, safety, oscillating, h}, or {reason} when there is
    no estimate. Where the finest three oscillate (the differences change sign) nothing is extrapolated:
    the value is the finest run's and the uncertainty half the range of the three."""
    pts = sorted((float(a), float(b)) for a, b in zip(h, f) if a is not None and b is not None
                 and math.isfinite(float(a)) and math.isfinite(float(b)))
    if len(pts) < 2:
        return {"reason": "fewer than two resolutions with a value"}
    oscillating = False
    if len(pts) >= 3:
        (h1, f1), (h2, f2), (h3, f3) = pts[:3]
        p, s = three_grid_order((h1, h2, h3), (f1, f2, f3))
        if p is None:
            return {"reason": "no observed order (equal values at two resolutions)"}
        if p <= 0:
            return {"reason": "the differences grow with refinement (order %.2f): not converging" % p, "order": p}
        if s < 0:  # oscillating: no extrapolation; the finest value, uncertain by half the range (Stern et al. 2001)
            return {"value": f1, "uncertainty": (max(f1, f2, f3) - min(f1, f2, f3)) / 2.0,
                    "gci": (max(f1, f2, f3) - min(f1, f2, f3)) / 2.0 / abs(f1) if f1 else None, "order": p,
                    "observed": True, "safety": None, "oscillating": True, "h": [h1, h2, h3]}
        oscillating, observed, safety = False, True, 1.25
    else:
        if not assumed_order:
            return {"reason": "two resolutions and no assumed order"}
        (h1, f1), (h2, f2) = pts
        p, observed, safety = float(assumed_order), False, 3.0
    if h2 <= h1:
        return {"reason": "equal h at the two finest resolutions"}
    denom = (h2 / h1) ** p - 1
    value = f1 + (f1 - f2) / denom
    unc = safety * abs(f1 - f2) / denom
    return {"value": value, "uncertainty": unc, "gci": unc / abs(f1) if f1 else None, "order": p,
            "observed": observed, "safety": safety, "oscillating": oscillating, "h": [h1, h2] + (
                [pts[2][0]] if observed else [])}
