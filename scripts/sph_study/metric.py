"""The study's metric: an error norm of summary.json (a plain name, e.g. l1_velocity) or a reduction of
a timeseries.csv column over a time window, e.g. {column: force_baffle_x, reduce: integral, from: 0, to: 1},
optionally of the column's centred moving average (smooth: W). Parsing and checking the study file's
'metric', reading a run's time series and reducing a column."""

import csv
import math
import os

from .common import read_json

REDUCTIONS = ("mean", "rms", "max", "min", "integral", "period", "amplitude")
COLUMN_KEYS = {"column", "reduce", "from", "to", "order", "smooth"}


def parse_metric(value, path):
    """The study file's 'metric' as {kind: summary, name} or {kind: column, column, reduce, from, to,
    order}; raises ValueError with a one-line message when it is malformed."""
    if isinstance(value, str) and value:
        return {"kind": "summary", "name": value}
    if not isinstance(value, dict):
        raise ValueError("%s: 'metric' must be an error name of summary.json (e.g. l1_velocity) or "
                         "{column: NAME, reduce: %s, from: T0, to: T1}" % (path, "|".join(REDUCTIONS)))
    bad = sorted(set(value) - COLUMN_KEYS)
    if bad:
        raise ValueError("%s: metric: unknown key(s) %s (known: %s)" % (path, ", ".join(map(str, bad)),
                                                                       ", ".join(sorted(COLUMN_KEYS))))
    column = value.get("column")
    if not isinstance(column, str) or not column:
        raise ValueError("%s: metric: 'column' must name a timeseries.csv column, e.g. force_baffle_x" % path)
    reduce = value.get("reduce", "mean")
    if reduce not in REDUCTIONS:
        raise ValueError("%s: metric: reduce '%s' is not one of %s" % (path, reduce, ", ".join(REDUCTIONS)))

    def number(key, default):
        v = value.get(key, default)
        try:  # YAML 1.1 reads 1e-3 (no dot) as a string
            v = float(v)
        except (TypeError, ValueError):
            raise ValueError("%s: metric: '%s' must be a number, got %r" % (path, key, value.get(key)))
        return v

    t_from, t_to = number("from", 0.0), number("to", math.inf)
    if not t_to > t_from:
        raise ValueError("%s: metric: 'to' (%g) must be after 'from' (%g)" % (path, t_to, t_from))
    order = value.get("order")
    if order is not None:
        order = number("order", None)
        if not order > 0:
            raise ValueError("%s: metric: 'order' (the order assumed with two resolutions) must be > 0" % path)
    smooth = number("smooth", 0.0)
    if not smooth >= 0:
        raise ValueError("%s: metric: 'smooth' (the moving average's width in time) must be >= 0" % path)
    return {"kind": "column", "column": column, "reduce": reduce, "from": t_from, "to": t_to, "order": order,
            "smooth": smooth}


def metric_label(m):
    """A short name of the metric for tables, plots and results.csv: l1_velocity, integral(force_baffle_x, 0..1)."""
    if m["kind"] == "summary":
        return m["name"]
    window = "" if m["from"] == 0 and m["to"] == math.inf else ", %g..%s" % (
        m["from"], "end" if m["to"] == math.inf else "%g" % m["to"])
    smooth = ", smoothed %g" % m["smooth"] if m.get("smooth") else ""
    return "%s(%s%s%s)" % (m["reduce"], m["column"], window, smooth)


def metric_words(m):
    """The metric in words for the report: 'the time integral of force_baffle_x over 0 <= t <= 1'."""
    if m["kind"] == "summary":
        return "the error norm `%s` of summary.json" % m["name"]
    what = {"mean": "the time mean", "rms": "the time RMS", "max": "the largest value", "min": "the smallest value",
            "integral": "the time integral (trapezoid over the steps)",
            "period": "the dominant period (mean time between upward crossings of the mean)",
            "amplitude": "the amplitude of a sinusoid fitted at the dominant period"}[m["reduce"]]
    window = "the whole run" if m["from"] == 0 and m["to"] == math.inf else (
        "%g ≤ t" % m["from"] if m["to"] == math.inf else "%g ≤ t ≤ %g" % (m["from"], m["to"]))
    column = ("the centred moving average over %g time units of `%s`" % (m["smooth"], m["column"])
              if m.get("smooth") else "`%s`" % m["column"])
    return "%s of %s over %s" % (what, column, window)


def read_timeseries(run_dir):
    """(header, {column: [float]}) of run_dir/timeseries.csv; empty cells and text read as nan."""
    with open(os.path.join(run_dir, "timeseries.csv"), newline="") as f:
        reader = csv.reader(f)
        header = next(reader, [])
        cols = {k: [] for k in header}
        for row in reader:
            for k, v in zip(header, row):
                try:
                    cols[k].append(float(v))
                except ValueError:
                    cols[k].append(math.nan)
    return header, cols


def timeseries_header(run_dir):
    try:
        with open(os.path.join(run_dir, "timeseries.csv"), newline="") as f:
            return next(csv.reader(f), [])
    except OSError:
        return None


def check_metric(m, run_dir):
    """None when the run at run_dir (a completed one) has the metric, else the one-line refusal naming what
    exists: its summary.json error names, or its timeseries.csv columns."""
    summary = read_json(os.path.join(run_dir, "summary.json")) or {}
    errors = list(summary.get("errors") or {})
    header = timeseries_header(run_dir) or []
    if m["kind"] == "summary":
        if m["name"] in errors:
            return None
        hint = (" (a timeseries.csv column: metric: {column: %s, reduce: mean|integral|..., from: T0, to: T1})" %
                m["name"]) if m["name"] in header else ""
        columns = [k for k in header if k not in ("step", "t")]
        return "metric '%s' is not an error of the runs%s; their errors: %s%s" % (
            m["name"], hint, ", ".join(errors) or "none (no reference solution)",
            "; timeseries.csv columns: " + ", ".join(columns) if columns else "")
    if m["column"] in header and m["column"] not in ("step", "t"):
        return None
    return "metric column '%s' is not in timeseries.csv; its columns: %s" % (
        m["column"], ", ".join(k for k in header if k not in ("step", "t")))


def window(t, f, t_from, t_to):
    """The samples (t, f) with t_from <= t <= t_to, the window's ends added by linear interpolation where
    the series covers them and by holding the nearest sample's value where it misses them by at most one
    step (1.5 times its longest; the series starts after the first step, at t = dt, not at 0). Raises
    ValueError otherwise."""
    pts = [(a, b) for a, b in zip(t, f) if math.isfinite(a)]
    if len(pts) < 2:
        raise ValueError("fewer than 2 steps in timeseries.csv")
    # The first row is at t = dt, and at rest the first step is often longer than any later one.
    step = 1.5 * max(b[0] - a[0] for a, b in zip(pts, pts[1:]))
    lo = max(t_from, pts[0][0] - step)
    hi = pts[-1][0] if t_to == math.inf else t_to
    if t_from < pts[0][0] - step * (1 + 1e-9) or hi > pts[-1][0] + step * (1 + 1e-9):
        raise ValueError("the run covers t = %g to %g only, not %g to %g" % (pts[0][0], pts[-1][0], t_from, hi))

    def at(x):
        if x <= pts[0][0]:
            return pts[0][1]
        if x >= pts[-1][0]:
            return pts[-1][1]
        for (a, fa), (b, fb) in zip(pts, pts[1:]):
            if a <= x <= b:
                return fa + (fb - fa) * (x - a) / (b - a) if b > a else fb
        return pts[-1][1]

    inside = [(a, b) for a, b in pts if lo < a < hi]
    out = [(lo, at(lo))] + inside + [(hi, at(hi))]
    if any(not math.isfinite(b) for _, b in out):
        raise ValueError("the column has empty or non-finite values in the window")
    return out


def trapezoid(pts):
    return sum((b[0] - a[0]) * (a[1] + b[1]) / 2.0 for a, b in zip(pts, pts[1:]))


def reduce_series(t, f, how, t_from=0.0, t_to=math.inf):
    """The reduction 'how' (REDUCTIONS) of the series f(t) over [t_from, t_to]. Mean and RMS are time
    averages (trapezoid), so they do not depend on how the steps are spaced. Raises ValueError."""
    pts = window(t, f, t_from, t_to)
    span = pts[-1][0] - pts[0][0]
    if how == "integral":
        return trapezoid(pts)
    if how == "max":
        return max(v for _, v in pts)
    if how == "min":
        return min(v for _, v in pts)
    if span <= 0:
        raise ValueError("the window is empty")
    mean = trapezoid(pts) / span
    if how == "mean":
        return mean
    if how == "rms":
        return math.sqrt(trapezoid([(a, v * v) for a, v in pts]) / span)
    period = dominant_period(pts, mean)
    if how == "period":
        return period
    return fitted_amplitude(pts, period)


def dominant_period(pts, mean):
    """Mean time between successive upward crossings of the mean (linear interpolation between steps)."""
    ups = []
    for (a, fa), (b, fb) in zip(pts, pts[1:]):
        if fa - mean < 0 <= fb - mean:
            ups.append(a + (b - a) * (mean - fa) / (fb - fa))
    if len(ups) < 2:
        raise ValueError("fewer than two upward crossings of the mean in the window: no period")
    return (ups[-1] - ups[0]) / (len(ups) - 1)


def fitted_amplitude(pts, period):
    """Amplitude of c + a cos(wt) + b sin(wt), w = 2 pi / period, fitted by least squares to the samples."""
    import numpy as np
    t = np.array([p[0] for p in pts])
    f = np.array([p[1] for p in pts])
    w = 2 * math.pi / period
    A = np.column_stack([np.ones_like(t), np.cos(w * t), np.sin(w * t)])
    coef = np.linalg.lstsq(A, f, rcond=None)[0]
    return float(math.hypot(coef[1], coef[2]))


def moving_average(t, f, width):
    """The centred moving average of the series f(t) over `width`, at each sample: the mean of its
    piecewise-linear interpolant over [t - width/2, t + width/2], cut to the series' span at its ends.
    WCSPH's forces carry the tank's acoustic ringing (docs/verification/free_surface.md, "WCSPH's force
    noise is the tank's sound"); this takes it out of a metric and leaves timeseries.csv as written."""
    import numpy as np
    t = np.asarray(t, dtype=float)
    f = np.asarray(f, dtype=float)
    if len(t) < 2 or width <= 0:
        return list(f)
    slope = np.diff(f) / np.where(np.diff(t) > 0, np.diff(t), 1.0)
    cumulative = np.concatenate([[0.0], np.cumsum(np.diff(t) * (f[:-1] + f[1:]) / 2)])

    def integral_to(x):  # exact for the interpolant: quadratic within a step
        i = np.clip(np.searchsorted(t, x, side="right") - 1, 0, len(t) - 2)
        d = x - t[i]
        return cumulative[i] + d * f[i] + d * d * slope[i] / 2

    a = np.maximum(t - width / 2, t[0])
    b = np.minimum(t + width / 2, t[-1])
    return list((integral_to(b) - integral_to(a)) / (b - a))


def metric_value(m, row):
    """(value, None) of the metric for a collected row, or (None, why not)."""
    if m["kind"] == "summary":
        v = row["errors"].get(m["name"])
        return (v, None) if isinstance(v, (int, float)) else (None, "not measured")
    if row["status"] != "completed":
        return None, row["status"]
    try:
        header, cols = read_timeseries(row["dir"])
    except (OSError, StopIteration) as e:
        return None, "no timeseries.csv (%s)" % e
    if m["column"] not in cols:
        return None, "no column %s" % m["column"]
    try:
        f = cols[m["column"]]
        if m.get("smooth"):
            f = moving_average(cols["t"], f, m["smooth"])
        return reduce_series(cols["t"], f, m["reduce"], m["from"], m["to"]), None
    except ValueError as e:
        return None, str(e)


def line_estimates(group, m, h_of):
    """A group's (one solver/sweep line) metric by resolution: [(row, h, value, why)] by increasing nx, the
    observed order of each successive three (None in the first two rows) and the Richardson estimate."""
    from .orders import richardson, three_grid_order
    pts = []
    for r in group:
        v, why = metric_value(m, r)
        pts.append((r, h_of(r), v, why))
    have = [(h, v) for _, h, v, _ in pts if v is not None and h]
    orders = []
    for _, h, v, _ in pts:
        k = [i for i, (hh, _) in enumerate(have) if hh == h and v is not None]
        if not k or k[0] < 2:
            orders.append(None)
            continue
        i = k[0]  # have runs coarse to fine: h decreases with i
        (h3, f3), (h2, f2), (h1, f1) = have[i - 2], have[i - 1], have[i]
        orders.append(three_grid_order((h1, h2, h3), (f1, f2, f3))[0])
    est = richardson([h for h, _ in have], [v for _, v in have], m.get("order") or 1.0)
    return pts, orders, est
