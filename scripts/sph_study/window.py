"""Error norms over a window of a run's time series. A steady flow's errors settle to a plateau that
still carries particle noise (the lid-driven cavity: the particles keep circulating, and the profile
interpolated from them moves by 0.1-0.3 points of U from step to step at nx 50), so the figure to read
is the mean over the plateau, not the value at the instant a run stopped."""

import csv
import math
import os

from sph_study.common import read_json

# timeseries.csv columns that are not error norms.
BOOKKEEPING = {"step", "t", "dt", "kinetic_energy", "momentum_x", "momentum_y", "momentum_z", "ksp_iterations",
               "ksp_reason"}


def window_statistics(run_dir, t_from, t_to=math.inf):
    """{norm: (mean, min, max)} over the steps of run_dir/timeseries.csv with t_from <= t <= t_to, and
    the (first, last) time and count of those steps. The mean weights each step's value by its dt, so
    that it is a time average whatever the steps. The norms are summary.json's error names where it
    has them, else every column that is not bookkeeping."""
    path = os.path.join(run_dir, "timeseries.csv")
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise ValueError(f"{path}: no steps")
    summary = read_json(os.path.join(run_dir, "summary.json")) or {}
    names = [k for k in summary.get("errors", {}) if k in rows[0]] or [k for k in rows[0] if k not in BOOKKEEPING]
    window = [r for r in rows if t_from <= float(r["t"]) <= t_to]
    if not window:
        raise ValueError(f"{path}: no step with {t_from} <= t <= {t_to} (the run has t = {rows[0]['t']} to "
                         f"{rows[-1]['t']})")
    weights = [float(r["dt"]) for r in window]
    stats = {}
    for name in names:
        values = [float(r[name]) for r in window if r[name] not in ("", "nan")]
        if len(values) != len(window):
            continue  # a norm missing at some steps is not averaged
        mean = sum(w * v for w, v in zip(weights, values)) / sum(weights)
        stats[name] = (mean, min(values), max(values))
    return stats, (float(window[0]["t"]), float(window[-1]["t"]), len(window))
