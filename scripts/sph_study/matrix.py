"""Stability matrix: rows = cases (with options), columns = scheme variants (solver + options); every
cell is one run, classified as ok / failed (during time stepping) / n/a (refused at start-up).
Planning is in plan.py (load_matrix, plan_matrix_runs); here: the cells, matrix.csv, matrix.md and the
matrix form of the command."""

import csv
import os
import re
import sys

from .common import REPO, read_json
from .execute import carry_out, study_settings
from .plan import option_args, plan_matrix_runs
from .report import fmt, fmt_wall, md_table, noted


def short_reason(msg, n=60):
    """A failure without its 'step N (t = ...): ' prefix, cut to about n characters."""
    msg = re.sub(r"^\s*step \d+ \(t = [^)]*\):\s*", "", (msg or "").strip()).replace("\n", " ")
    return msg if len(msg) <= n else msg[:n].rstrip() + "…"


def option_problem(msg):
    """True for start-up errors about the options themselves (a typo, a bad value): a study-file mistake,
    not a case the solver refuses."""
    return bool(re.match(r"^\s*-\w", msg or "")) or "option" in (msg or "").lower()


def classify_cell(run):
    """(status, reason, metric, value, wall_time_s, steps) of one matrix cell. status: ok, failed (during
    time stepping, or a timeout), n/a (the program refused the case/solver pair at start-up), error (a
    start-up error about the options), not run."""
    rec = read_json(os.path.join(run["dir"], "run.json")) or {}
    s = read_json(os.path.join(run["dir"], "summary.json")) or {}
    metric = run.get("metric")
    wall = s.get("wall_time_s", rec.get("elapsed_s"))
    steps = s.get("steps")
    if not rec and not s:
        return "not run", "", metric or "", None, None, None
    errors = s.get("errors") or {}
    if s and s.get("status", "completed") == "completed" and rec.get("status") != "failed":
        if not metric or metric not in errors:
            reason = "" if not metric else "no %s in summary.json" % metric
            metric = metric if not errors else (metric if metric in errors else list(errors)[0])
        elif errors[metric] is None:  # null: the run could not measure it; summary.json says why
            reason = "not measured: " + (s.get("errors_unmeasured") or {}).get(metric, "no reason given")
        else:
            reason = ""
        return "ok", reason, metric or "", errors.get(metric), wall, steps
    failure = s.get("failure") or rec.get("failure") or "unknown failure"
    if s or "timed out" in failure or rec.get("returncode") is None or (rec.get("returncode") or 0) < 0:
        return "failed", failure, metric or "", errors.get(metric), wall, steps
    if option_problem(failure):
        return "error", failure, metric or "", None, wall, steps
    return "n/a", failure, metric or "", None, wall, steps


# The causes of an energy budget that can only take energy out of a flow in a closed tank or a periodic
# box (src/sph/energy_budget.hpp): a positive total is energy the scheme created.
NON_POSITIVE_CAUSES = ("pressure", "viscous", "artificial_viscosity", "density_diffusion", "shifting",
                       "wall_bounding")


def largest_kinetic_energy(run_dir):
    """The largest kinetic_energy of a run's timeseries.csv (0 without one)."""
    try:
        with open(os.path.join(run_dir, "timeseries.csv"), newline="") as f:
            return max((float(r["kinetic_energy"]) for r in csv.DictReader(f)), default=0.0)
    except (OSError, KeyError, ValueError):
        return 0.0


def energy_figures(run):
    """(created, scale) from a cell's energy budget (summary.json conservation.energy_budget), or None
    without one: the summed positive totals of the causes that should only remove energy, and the scale
    they are measured against, the largest kinetic energy of the run (at the start, or in any step's
    row of timeseries.csv) or the kinetic energy gravity's kicks gave, if larger. A flow that should
    stay at rest (still water) has only spurious motion to measure against: a large share there says
    that the scheme's own motion is what it created."""
    s = read_json(os.path.join(run["dir"], "summary.json")) or {}
    b = (s.get("conservation") or {}).get("energy_budget")
    if not b:
        return None
    work = b.get("work") or {}
    created = sum(max(0.0, work.get(c, 0.0)) for c in NON_POSITIVE_CAUSES)
    scale = max([abs(b.get(k, 0.0)) for k in ("kinetic_energy_start", "kinetic_energy_end", "gravity_released")] +
                [largest_kinetic_energy(run["dir"])])
    return created, scale


def energy_text(e):
    """', energy +x %' (created over scale) for an ok cell with a budget; '' without one."""
    if e is None or not e[1] > 0:
        return ""
    return ", energy +%s %%" % fmt(100.0 * e[0] / e[1], "%.2g")


def cell_text(c):
    status, reason, metric, value, wall, steps = c
    if status == "ok":
        t = "ok, %s=%s" % (metric, fmt(value, "%.3g")) if value is not None else "ok" + (" (%s)" % reason if reason else "")
        return t + (" (%s)" % fmt_wall(wall) if isinstance(wall, (int, float)) else "")
    if status == "failed":
        return "**failed**: %s" % short_reason(reason)
    if status == "n/a":
        return "n/a (%s)" % short_reason(reason, 80)
    if status == "error":
        return "**error**: %s" % short_reason(reason, 80)
    return status


def energy_cell_text(run, c):
    """cell_text with an ok cell's energy created inserted before its wall time."""
    text = cell_text(c)
    if c[0] != "ok":
        return text
    extra = energy_text(energy_figures(run))
    cut = text.rfind(" (")
    return text[:cut] + extra + text[cut:] if cut > 0 and text.endswith(")") else text + extra


def make_matrix_outputs(study, study_file, runs, out_dir, counts):
    m = study["matrix"]
    cells = {(r["row"], r["column"]): (r, classify_cell(r)) for r in runs}
    with open(os.path.join(out_dir, "matrix.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["row", "column", "status", "reason", "metric", "value", "wall_time_s", "steps",
                    "energy_created", "energy_scale", "run_dir"])
        for r in runs:
            status, reason, metric, value, wall, steps = cells[(r["row"], r["column"])][1]
            e = energy_figures(r)
            w.writerow([r["row"], r["column"], status, short_reason(reason, 10 ** 6), metric,
                        "" if value is None else value, "" if wall is None else wall, "" if steps is None else steps,
                        "" if e is None else e[0], "" if e is None else e[1], os.path.relpath(r["dir"], out_dir)])
    cols = [c["label"] for c in m["columns"]]
    L = ["# Stability matrix: %s" % study["name"], ""]
    if study.get("description"):
        L += [str(study["description"]).strip(), ""]
    ran, skipped, failed = counts
    L += ["Study file `%s`; %d cells (%d run now, %d up to date). Cells: **ok**, the row's error norm, the "
          "energy the scheme created (the positive totals of the budget's pressure, viscous, artificial "
          "viscosity, density diffusion, shifting and wall bounding terms, in %% of the run's largest kinetic "
          "energy or of what gravity gave; a moving wall, the cavity's lid, feeds energy in through the "
          "pressure and viscous terms) and the wall time; **failed**: the run stopped during time stepping (reason); **n/a**: the program refuses "
          "this case with this solver at start-up; **error**: a start-up error about the options." %
          (os.path.relpath(os.path.abspath(study_file), REPO) if os.path.abspath(study_file).startswith(REPO)
           else study_file, len(runs), ran, skipped), ""]
    L += ["Columns: " + "; ".join("**%s** = `-solver %s%s`" % (c["label"], c["solver"],
                                   "".join(" " + a for a in option_args(c["options"]))) for c in m["columns"]), ""]
    body = []
    for row in m["rows"]:
        body.append([row["label"]] + [energy_cell_text(*cells[(row["label"], c)]).replace("|", "\\|") for c in cols])
    L += [noted(md_table(["case"] + cols, body, align=["---"] * (len(cols) + 1))), ""]
    L += ["Per case:", ""]
    for row in m["rows"]:
        cs = [(c, cells[(row["label"], c)][1]) for c in cols]
        ok = [(c, x) for c, x in cs if x[0] == "ok"]
        parts = []
        if ok:
            best = [(x[3], c) for c, x in ok if isinstance(x[3], (int, float))]
            s = "survived with %s" % ", ".join(c for c, _ in ok)
            if len(best) > 1:
                v, c = min(best)
                s += " (lowest `%s`: %s, %.3g)" % (ok[0][1][2], c, v)
            parts.append(s)
        else:
            parts.append("no variant survived")
        for st, word in (("failed", "failed"), ("n/a", "not applicable"), ("error", "option errors"),
                         ("not run", "not run")):
            names = [c for c, x in cs if x[0] == st]
            if names:
                parts.append("%s: %s" % (word, ", ".join(names)))
        L.append("- **%s** (`-case %s%s`): %s." % (row["label"], row["case"],
                 "".join(" " + a for a in option_args(row["options"])), "; ".join(parts)))
    L += [""]
    details = [(r, cells[(r["row"], r["column"])][1]) for r in runs]
    details = [(r, c) for r, c in details if c[0] in ("failed", "n/a", "error")]
    if details:
        L += ["Full reasons:", ""]
        L += ["- %s × %s: %s (`%s`)" % (r["row"], r["column"], c[1].replace("\n", " "),
                                        os.path.relpath(r["dir"], out_dir)) for r, c in details]
        L += [""]
    L += ["Every cell's exact command is in its folder's `run.json`; outputs in `summary.json`, `stderr.txt`. "
          "All cells: `matrix.csv`.", ""]
    with open(os.path.join(out_dir, "matrix.md"), "w") as f:
        f.write("\n".join(L))


def main_matrix(a, study):
    """The 'matrix:' form: every (row, column) cell once; matrix.csv and matrix.md."""
    if a.nx:
        sys.exit("study: --nx does not apply to a matrix study (set nx in the rows' options)")
    mpi, sph, out_dir = study_settings(a, study)
    runs = plan_matrix_runs(study, out_dir, sph, mpi)
    counts = carry_out(a, runs, sph, out_dir, None)
    if counts is None:
        return 0
    make_matrix_outputs(study, a.study, runs, out_dir, counts)
    tally = {}
    for r in runs:
        st = classify_cell(r)[0]
        tally[st] = tally.get(st, 0) + 1
    print("matrix: " + ", ".join("%d %s" % (tally[k], k) for k in ("ok", "failed", "n/a", "error", "not run")
                                 if tally.get(k)))
    print("wrote %s" % os.path.join(out_dir, "matrix.md"))
    return 0
