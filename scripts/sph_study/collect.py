"""Results table: the run folders' run.json and summary.json as rows, results.csv, rows grouped into lines."""

import csv
import os

from .common import read_json


def collect(runs):
    rows = []
    for r in runs:
        rec = read_json(os.path.join(r["dir"], "run.json")) or {}
        s = read_json(os.path.join(r["dir"], "summary.json")) or {}
        status = s.get("status") or rec.get("status") or "not run"
        if rec.get("status") == "failed":
            status = "failed"
        failure = s.get("failure") or rec.get("failure") or ""
        ksp = s.get("ksp") or {}
        row = {"load": rec.get("busy_cores_at_start", rec.get("load_average_at_start")), "cpus": rec.get("cpus"), "label": r["label"], "solver": r["solver"], "sweep": r["sweep"], "nx": r["nx"],
               "N": s.get("n_particles"), "h": (s.get("kernel") or {}).get("h"), "steps": s.get("steps"),
               "wall_time_s": s.get("wall_time_s"), "time_per_particle_step_s": s.get("time_per_particle_step_s"),
               "ksp_iterations_mean": ksp.get("iterations_mean") if ksp else None,
               "ksp_iterations_max": ksp.get("iterations_max") if ksp else None,
               "status": status, "failure": failure, "errors": dict(s.get("errors") or {}),
               "steady_state_reached": s.get("steady_state_reached"),
               "dir": r["dir"], "run": r}
        rows.append(row)
    return rows


def error_names(rows):
    names = []
    for row in rows:
        for k in row["errors"]:
            if k not in names:
                names.append(k)
    return names


def write_csv(path, rows, sweep_keys, errors, metric=None):
    """metric: the name of a time-series metric's column (its value in row["metric_value"]), or None."""
    cols = sweep_keys + ["solver", "nx", "N", "h", "steps", "wall_time_s", "time_per_particle_step_s",
                         "ksp_iterations_mean", "ksp_iterations_max", "status", "failure", "steady_state_reached"] + errors + (
                             [metric] if metric else []) + ["run_dir"]
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in rows:
            vals = [r["sweep"].get(k, "") for k in sweep_keys]
            vals += [r[c] if r[c] is not None else "" for c in
                     ("solver", "nx", "N", "h", "steps", "wall_time_s", "time_per_particle_step_s",
                      "ksp_iterations_mean", "ksp_iterations_max", "status", "failure", "steady_state_reached")]
            vals += [r["errors"].get(e, "") for e in errors]
            if metric:
                vals.append("%.17g" % r["metric_value"] if r.get("metric_value") is not None else "")
            vals.append(os.path.relpath(r["dir"], os.path.dirname(path)))
            w.writerow(vals)


def groups_of(rows):
    """Rows grouped by solver + sweep values (plot lines / report tables), in study order."""
    groups = {}
    for r in rows:
        groups.setdefault(r["label"], []).append(r)
    for g in groups.values():
        g.sort(key=lambda r: r["nx"])
    return groups


def completed(rows):
    return [r for r in rows if r["status"] == "completed"]


def line_points(group, metric, x):
    """[(x, |error|, error < 0, row)] of the completed runs of one group having both values and a nonzero
    error. Log axes show a signed error (amplitude_rel) by its magnitude; the sign is kept for the marker."""
    pts = []
    for r in completed(group):
        e = r["errors"].get(metric)
        xv = r.get(x)
        if isinstance(e, (int, float)) and isinstance(xv, (int, float)) and e != 0 and xv > 0:
            pts.append((float(xv), abs(float(e)), e < 0, r))
    return pts
