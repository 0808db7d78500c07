"""Report: report.md of a convergence study, and every output of one (results.csv, plots, report.md)."""

import datetime
import os
import sys

from .collect import collect, completed, error_names, groups_of, write_csv
from .common import NOISE_WALL_S, REPO, noisy_wall
from .metric import check_metric, line_estimates, metric_label, metric_words, metric_value, parse_metric
from .orders import observed_order, pareto_table
from .plan import option_args, option_value
from .plots import (figure_all_errors_vs_h, figure_centrelines, figure_error_vs_h, figure_ksp, figure_metric_vs_h,
                    figure_pareto, plotting, save)

NOISE_MARK = "†"
NOISE_NOTE = "%s wall time < %g s: timer noise, not a measure of speed." % (NOISE_MARK, NOISE_WALL_S)


def md_table(header, rows, align=None):
    out = ["| " + " | ".join(header) + " |",
           "|" + "|".join(align or ["---:" if i else "---" for i in range(len(header))]) + "|"]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(out)


def fmt_time(t):
    if t is None:
        return "–"
    if t < 10:
        return "%.3g s" % t
    return "%.0f s" % t


def fmt_wall(t):
    """fmt_time of a wall time, marked when it is noise."""
    return flag_noise(t, fmt_time(t))


def fmt(v, spec="%.4g"):
    if v is None or v == "":
        return ""
    if isinstance(v, float):
        return spec % v
    return str(v)


def flag_noise(wall, text):
    """A table cell measured over a wall time: marked when that wall time is noise (kept, not dropped)."""
    return text + NOISE_MARK if text and noisy_wall(wall) else text


def noted(table):
    """A table, followed by the noise footnote where a cell of it is marked."""
    return table + ("\n\n" + NOISE_NOTE if NOISE_MARK in table else "")


def h_of(row):
    """A run's smoothing length (summary.json), else 1/nx: the refinement ratios are the same."""
    return row["h"] if isinstance(row.get("h"), (int, float)) and row["h"] > 0 else (1.0 / row["nx"] if row["nx"] else None)


def fmt_value(v):
    return "–" if v is None else "%.6g" % v


def estimate_text(est):
    """The Richardson estimate in words: value ± GCI uncertainty, the order and factor of safety used."""
    if "value" not in est:
        return "no Richardson estimate: %s" % est["reason"]
    if est["oscillating"]:
        return "none: the finest three oscillate (observed order %.2f); the finest value %s ± %s (half the range " \
            "of the three)" % (est["order"], fmt_value(est["value"]), "%.2g" % est["uncertainty"])
    return "%s ± %s (GCI %s, %s order %.2f, factor of safety %g%s)" % (
        fmt_value(est["value"]), "%.2g" % est["uncertainty"],
        "%.2g %%" % (100 * est["gci"]) if est["gci"] is not None else "–",
        "observed" if est["observed"] else "assumed", est["order"], est["safety"], "")


def metric_section(m, groups):
    """Lines of report.md for a time-series metric: per line its value by resolution, the observed order
    of each three successive resolutions and the Richardson estimate; then every line in one table."""
    label = metric_label(m)
    L = ["## Metric `%s`" % label, "",
         "%s, per run. Observed order p from three successive resolutions (in the row of the finest), "
         "solving p ln r₂₁ = ln(e₃₂/e₂₁) + ln((r₂₁ᵖ − s)/(r₃₂ᵖ − s)) for any refinement ratios r = h_coarse/h_fine "
         "(e: the differences between successive values, s their sign ratio). Richardson extrapolation "
         "to h → 0 from the finest three, with the uncertainty of Roache's grid convergence index "
         "(GCI = Fs |f₁ − f₂| / (r₂₁ᵖ − 1), factor of safety Fs 1.25); from two resolutions with an assumed "
         "order (%g%s) and Fs 3." % (metric_words(m)[0].upper() + metric_words(m)[1:], m.get("order") or 1,
                                      "" if m.get("order") else ", `order:` in the metric sets it"), ""]
    results = {}
    for name, g in groups.items():
        pts, orders, est = line_estimates(g, m, h_of)
        results[name] = (pts, orders, est)
        body = []
        prev = None
        for (r, h, v, why), p in zip(pts, orders):
            change = fmt_value(v - prev) if v is not None and prev is not None else ""
            body.append([r["nx"], fmt(h), fmt_value(v) if v is not None else "– (%s)" % why.replace("|", "\\|"),
                         change, fmt(p, "%.2f")])
            prev = v if v is not None else prev
        L += ["### %s" % name, "", md_table(["nx", "h", label, "change", "observed order"], body), "",
              "Richardson estimate: %s." % estimate_text(est), ""]
    if len(groups) > 1:
        names = list(groups)
        L += ["### %s against each other" % " and ".join(names), ""]
        nxs = sorted({r["nx"] for pts, _, _ in results.values() for r, _, _, _ in pts})
        body = []
        for nx in nxs:
            cells = ["nx = %d" % nx]
            for n in names:
                v = [v for r, _, v, _ in results[n][0] if r["nx"] == nx]
                cells.append(fmt_value(v[0]) if v else "")
            body.append(cells)
        ests = [results[n][2] for n in names]
        body.append(["observed order (finest three)"] + [
            "– (assumed %g)" % e["order"] if e.get("observed") is False else fmt(e.get("order"), "%.2f") or "–"
            for e in ests])
        body.append(["Richardson estimate (h → 0)"] + [
            "none: oscillates (finest %s)" % fmt_value(e["value"]) if e.get("oscillating") else fmt_value(e.get("value"))
            for e in ests])
        body.append(["uncertainty (±: GCI, or half the range where it oscillates)"] + ["%.2g" % e["uncertainty"] if "value" in e else "– (%s)" % e["reason"]
                                                for e in ests])
        body.append(["relative uncertainty (of the finest run)"] + ["%.2g %%" % (100 * e["gci"]) if e.get("gci") is not None else "–"
                                                 for e in ests])
        L += [md_table([label] + names, body), ""]
        good = [(n, e) for n, e in zip(names, ests) if "value" in e]
        for (a, ea), (b, eb) in zip(good, good[1:]):
            d = abs(ea["value"] - eb["value"])
            both = ea["uncertainty"] + eb["uncertainty"]
            L += ["The estimates of `%s` and `%s` are %s apart: %s the sum of their uncertainties (%.2g)." % (
                a, b, "%.2g" % d, "within" if d <= both else "**beyond**", both)]
        L += [""]
    return L, results


def write_report(path, study, study_file, rows, groups, errors, metric, plots, pareto, counts, jobs, mpi, notes,
                 metric_lines=None):
    name = study["name"]
    spec = study.get("metric_spec") or {"kind": "summary"}
    L = ["# Study `%s`" % name, ""]
    if study.get("description"):
        L += [str(study["description"]).strip(), ""]
    fixed = dict(study["options"])
    L += ["Case `%s`, solvers %s, resolutions nx = %s. Study file `%s`; generated %s by `scripts/study`%s." % (
        study["case"], ", ".join("`%s`" % s for s in study["solvers"]),
        ", ".join(str(n) for n in study["resolutions"]), os.path.relpath(study_file, REPO)
        if os.path.abspath(study_file).startswith(REPO + os.sep) else study_file,
        datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
        " with `-j %d`" % jobs if jobs > 1 else "") + (" MPI ranks per run: %d." % mpi if mpi else ""), ""]
    if fixed:
        L += ["Fixed options: " + " ".join("`%s`" % " ".join(option_args({k: v})) for k, v in fixed.items()) + "."]
    for solver, opts in study["solver_options"].items():
        if opts:
            L += ["Options of `%s` only: " % solver + " ".join("`%s`" % " ".join(option_args({k: v}))
                                                            for k, v in opts.items()) + "."]
    for who, table in [("every solver", study["resolution_options"])] + [
            ("`%s`" % k, v) for k, v in study["solver_resolution_options"].items()]:
        if table:
            L += ["Options refined with h (%s): " % who + "; ".join(
                "`-%s` %s at nx = %s" % (k, ", ".join(option_value(x) or "" for x in v),
                                         ", ".join(str(n) for n in study["resolutions"]))
                for k, v in table.items()) + "."]
    ran, skipped, failed = counts
    n_ok = len(completed(rows))
    # A scene has no reference solution: its runs report no error norm, and the report says so.
    measured = any(r["errors"] for r in rows) and spec["kind"] == "summary"
    L += ["", "Runs: %d in all, %d completed, %d failed (the last invocation ran %d and found %d up to date). " %
          (len(rows), n_ok, len([r for r in rows if r["status"] == "failed"]), ran, skipped) +
          ("Error metric of the plots and the speed comparison: `%s`. Observed order between successive "
           "resolutions: p = log(e₁/e₂) / log(h₁/h₂), shown in the row of the finer run." % metric if measured else
           ("Metric: %s (section below)." % metric_words(spec) if spec["kind"] == "column" else
            "The runs report no error norm (a scene has no reference solution): the tables give their status, "
            "steps, wall time and KSP iterations.")), ""]
    if jobs > 1:
        L += ["Note: runs were made %d at a time, so wall times include contention for the cores." % jobs, ""]
    # One run at a time: other work on more than half a core at a run's start. Several at a time: the
    # load average, which then counts the study's own runs, beyond the core count.
    limit = (lambda r: 0.5) if jobs <= 1 else (lambda r: r["cpus"])
    busy = [r for r in rows if r.get("load") is not None and r.get("cpus") and r["load"] > limit(r)]
    if busy:
        which = ("all %d runs" % len(busy) if len(busy) == len(rows) else
                 "; ".join("%s nx=%d" % (r["label"], r["nx"]) for r in busy[:6]) + ("; …" if len(busy) > 6 else ""))
        L += ["Note: %s started while other work kept up to %.1f of the %d cores busy: wall times may be "
              "inflated." % (which, max(r["load"] for r in busy), busy[0]["cpus"]), ""]

    L += metric_lines or []
    # Observed orders at a glance: finest pair of every line and norm.
    L += ["## Observed orders (finest pair of resolutions)", ""] if errors else []
    hdr = ["solver / sweep", "nx pair"] + errors
    body = []
    for label, g in groups.items():
        ok = [r for r in completed(g) if r["h"]]
        if len(ok) < 2:
            body.append([label, "–"] + ["" for _ in errors])
            continue
        a, b = ok[-2], ok[-1]
        body.append([label, "%d→%d" % (a["nx"], b["nx"])] +
                    [fmt(observed_order(a["errors"].get(e), b["errors"].get(e), a["h"], b["h"]), "%.2f")
                     for e in errors])
    L += [md_table(hdr, body), ""] if errors else []
    remarks = []
    for label, g in groups.items():
        ok = [r for r in completed(g) if isinstance(r["errors"].get(metric), (int, float)) and r["h"]]
        for a, b in zip(ok, ok[1:]):
            if b["errors"][metric] > a["errors"][metric]:
                remarks.append("`%s`: `%s` grows from nx=%d to nx=%d (%.3g → %.3g)." % (
                    label, metric, a["nx"], b["nx"], a["errors"][metric], b["errors"][metric]))
        if len(ok) >= 2:
            p = observed_order(ok[-2]["errors"][metric], ok[-1]["errors"][metric], ok[-2]["h"], ok[-1]["h"])
            if p is not None and 0 <= p < 0.5:
                remarks.append("`%s`: `%s` stagnates between nx=%d and nx=%d (order %.2f): an error floor "
                               "independent of h dominates there." % (label, metric, ok[-2]["nx"], ok[-1]["nx"], p))
    if remarks:
        L += ["Remarks on `%s`:" % metric, ""] + ["- " + m for m in remarks] + [""]

    L += ["## Results", ""]
    for label, g in groups.items():
        L += ["### %s" % label, ""]
        isph_like = any(r["ksp_iterations_mean"] is not None for r in g)
        hdr = ["nx", "status", "steady state", "N", "h", "steps", "wall [s]", "s / (particle·step)"]
        if isph_like:
            hdr.append("KSP its per step, mean / max")
        for e in errors:
            hdr += [e, "order"]
        body = []
        prev = None
        for r in g:
            # steady state: reached or not where the run checked for it, "–" where it did not.
            steady = {True: "reached", False: "not reached"}.get(r["steady_state_reached"], "–")
            if r["status"] != "completed":
                body.append([r["nx"], "**%s**" % r["status"], steady, fmt(r["N"]), "", "", "", "",
                             *([""] if isph_like else []), r["failure"].replace("|", "\\|")] +
                            [""] * (2 * len(errors) - 1))
                continue
            wall = r["wall_time_s"]
            row = [r["nx"], r["status"], steady, fmt(r["N"]), fmt(r["h"]), fmt(r["steps"]),
                   flag_noise(wall, fmt(wall, "%.3g")), flag_noise(wall, fmt(r["time_per_particle_step_s"], "%.3g"))]
            if isph_like:
                row.append("%s / %s" % (fmt(r["ksp_iterations_mean"], "%.1f"), fmt(r["ksp_iterations_max"]))
                           if r["ksp_iterations_mean"] is not None else "")
            for e in errors:
                # null in summary.json: the run could not measure it (summary.json says why)
                row.append("not measured" if e in r["errors"] and r["errors"][e] is None else fmt(r["errors"].get(e), "%.3e"))
                row.append(fmt(observed_order(prev["errors"].get(e), r["errors"].get(e), prev["h"], r["h"]), "%.2f")
                           if prev else "")
            body.append(row)
            prev = r
        L += [noted(md_table(hdr, body)), ""]

    failed_rows = [r for r in rows if r["status"] == "failed"]
    if failed_rows:
        L += ["## Failed runs", ""]
        L += ["- `%s` nx=%d: %s (folder `%s`)" % (r["label"], r["nx"], r["failure"],
                                                   os.path.relpath(r["dir"], os.path.dirname(path)))
              for r in failed_rows]
        L += [""]

    L += ["## Speed against accuracy", ""]
    if spec["kind"] == "column":
        L += ["The metric `%s` is not an error against a reference: no speed-against-accuracy table." % metric, ""]
    elif pareto:
        labels = [l for l in groups if any(l in row["times"] for row in pareto)]
        L += ["Wall time each line needs to reach a `%s` level, interpolated log-log between successive "
              "resolutions (≤: already reached by the coarsest run; –: not reached):" % metric, ""]
        hdr = ["%s ≤" % metric] + labels + ["fastest", "speed-up vs next"]
        body = []
        for row in pareto:
            cells = ["%.3g" % row["level"]]
            for l in labels:
                t, exact = row["times"].get(l, (None, False))
                cells.append(("" if exact or t is None else "≤ ") + fmt_wall(t))
            cells += [row["best"] or "none", "%.2f×" % row["speedup"] if row["speedup"] else ""]
            body.append(cells)
        L += [noted(md_table(hdr, body)), ""]
        L += ["In words:", ""]
        for row in pareto:
            if not row["best"]:
                L.append("- `%s` ≤ %.3g: no run reached it." % (metric, row["level"]))
            elif row["runner_up"]:
                L.append("- `%s` ≤ %.3g: **%s** is ahead (%s against %s for %s, %.2f× faster)." % (
                    metric, row["level"], row["best"], fmt_wall(row["times"][row["best"]][0]),
                    fmt_wall(row["times"][row["runner_up"]][0]), row["runner_up"], row["speedup"]))
            else:
                L.append("- `%s` ≤ %.3g: only **%s** reaches it (%s)." % (
                    metric, row["level"], row["best"], fmt_wall(row["times"][row["best"]][0])))
        L += [""]
    else:
        L += ["No completed runs with the metric `%s` and a wall time." % metric, ""]

    if plots:
        L += ["## Plots", ""]
        for title, fname in plots:
            pdf = os.path.splitext(fname)[0] + ".pdf"
            L += ["### %s" % title, "", "![%s](%s)" % (title, fname), "", "Vector version: [%s](%s)." % (pdf, pdf), ""]
    if notes:
        L += ["## Notes", ""] + ["- " + n for n in notes] + [""]
    L += ["Every run's inputs and exact command are in its folder's `run.json`; its outputs in `summary.json`, "
          "`timeseries.csv`, `stderr.txt`. All rows: `results.csv`.", ""]
    with open(path, "w") as f:
        f.write("\n".join(L))


def write_figures(plt, study, groups, errors, metric, out_dir, notes, estimates=None):
    """Every figure there is something to draw, as PNG and PDF; returns [(caption, PNG file name)]."""
    title = study["name"] if study["case"] in study["name"] else "%s: %s" % (study["name"], study["case"])
    centrelines, note = figure_centrelines(plt, groups, study["case"], study["options"], title)
    if note:
        notes.append("centreline plot: " + note)
    figures = [
        ("%s against h, extrapolated to h → 0" % metric, "metric_vs_h.png",
         figure_metric_vs_h(plt, estimates, metric, title)) if estimates else ("", "", None),
        ("%s against h" % metric, "error_vs_h.png", figure_error_vs_h(plt, groups, metric, title)),
        ("Every error norm against h", "errors_vs_h.png", figure_all_errors_vs_h(plt, groups, errors, title)),
        ("%s against wall time (speed–accuracy)" % metric, "pareto.png",
         figure_pareto(plt, groups, metric, title + ", speed against accuracy")),
        ("KSP iterations per time step against N", "ksp_iterations.png",
         figure_ksp(plt, groups, title + ", pressure solves")),
        ("Centreline velocity profiles", "centrelines.png", centrelines),
    ]
    plots = []
    for caption, fname, fig in figures:
        if fig is not None:
            save(plt, fig, os.path.join(out_dir, fname))
            plots.append((caption, fname))
    return plots


def make_outputs(study, study_file, runs, out_dir, counts, jobs, mpi):
    rows = collect(runs)
    errors = error_names(rows)
    metric = study["metric"]
    spec = study.get("metric_spec")
    if not spec or metric_label(spec) != metric:
        spec = study["metric_spec"] = parse_metric(metric, study_file)
    notes = []
    first = next((r for r in rows if r["status"] == "completed"), None)
    # A metric the study file names must exist: refused, naming what the runs have (not silently replaced).
    if first and (spec["kind"] == "column" or study.get("metric_given")):
        refusal = check_metric(spec, first["dir"])
        if refusal:
            sys.exit("study: " + refusal)
    if errors and metric not in errors and spec["kind"] == "summary":
        notes.append("metric `%s` is not among the errors of the runs (%s); using `%s`" %
                     (metric, ", ".join(errors), errors[0]))
        print("study: metric %s not found; using %s" % (metric, errors[0]), file=sys.stderr)
        metric = errors[0]
    sweep_keys = []
    for r in runs:
        for k in r["sweep"]:
            if k not in sweep_keys:
                sweep_keys.append(k)
    metric_lines, estimates = [], {}
    if spec["kind"] == "column":
        for r in rows:
            r["metric_value"] = metric_value(spec, r)[0]
        metric_lines, estimates = metric_section(spec, groups_of(rows))
    write_csv(os.path.join(out_dir, "results.csv"), rows, sweep_keys, errors,
              metric if spec["kind"] == "column" else None)
    errors = [metric] + [e for e in errors if e != metric] if metric in errors else errors
    groups = groups_of(rows)
    lines = {}
    for label, g in groups.items():
        pts = [(r["wall_time_s"], r["errors"].get(metric)) for r in completed(g)]
        pts = [(t, e) for t, e in pts if isinstance(t, (int, float)) and isinstance(e, (int, float))]
        if pts:
            lines[label] = pts
    pareto = pareto_table(lines, study.get("levels"))
    plots = []
    plt = plotting()
    if plt is not None:
        plots = write_figures(plt, study, groups, errors, metric, out_dir, notes, estimates)
    else:
        notes.append("plots skipped: matplotlib is not available to this Python")
    write_report(os.path.join(out_dir, "report.md"), study, study_file, rows, groups, errors, metric, plots,
                 pareto, counts, jobs, mpi, notes, metric_lines)
    return rows
