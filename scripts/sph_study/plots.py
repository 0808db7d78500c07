"""Plots (matplotlib, imported only when plotting): errors against h, speed against accuracy, KSP
iterations, lid-driven cavity centrelines against Ghia et al. (1982). The figure_* functions build a
figure (None when there is nothing to draw); save() writes it as PNG and PDF."""

import csv
import os
import re
import sys

from .collect import completed, line_points
from .common import NOISE_WALL_S, REPO, noisy_wall, read_json


def plotting():
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        plt.rcParams.update({"figure.dpi": 100, "savefig.dpi": 100, "font.size": 10, "axes.grid": True,
                             "grid.alpha": 0.3, "grid.linestyle": ":", "legend.fontsize": 8,
                             # TrueType in the PDFs: publishers' checks reject the default Type 3 fonts
                             "pdf.fonttype": 42})
        return plt
    except ImportError:
        print("study: matplotlib not available (Debian: python3-matplotlib; run with /usr/bin/python3): "
              "plots skipped", file=sys.stderr)
        return None


MARKERS = "osD^vP*Xh<>"


def style(i):
    import matplotlib.pyplot as plt
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    return {"color": colors[i % len(colors)], "marker": MARKERS[i % len(MARKERS)]}


def tidy_log_axis(ax, which, ticks=None, integer=False):
    """Readable log axis: ticks at the given data values (e.g. the h of the runs) or at 1-2-5 x 10^k,
    plain number labels, no minor labels (the default ones overlap on short ranges)."""
    import matplotlib.ticker as mt
    axis = ax.xaxis if which == "x" else ax.yaxis
    label = mt.FuncFormatter((lambda v, _: "%d" % round(v)) if integer else (lambda v, _: "%g" % float("%.3g" % v)))
    if ticks:
        axis.set_major_locator(mt.FixedLocator(sorted(set(ticks))))
    else:
        lo, hi = (ax.get_xlim() if which == "x" else ax.get_ylim())
        span = hi / lo if lo > 0 else 1e9
        subs = tuple(range(1, 10)) if span < 8 else (1.0, 2.0, 5.0) if span < 1e3 else (1.0,)
        axis.set_major_locator(mt.LogLocator(base=10, subs=subs))
    axis.set_major_formatter(label)
    axis.set_minor_formatter(mt.NullFormatter())


def outside_legend(ax, notes=(), **kw):
    """Legend right of the axes: never covers data or point labels, whatever the label lengths. notes:
    extra entries (marker_notes) after the lines'."""
    handles = ax.get_legend_handles_labels()[0] + list(notes)
    ax.legend(handles, [h.get_label() for h in handles], loc="upper left", bbox_to_anchor=(1.02, 1.0),
              borderaxespad=0.0, title_fontsize=8, **kw)


def reference_slopes(ax, hs, es, orders=(1, 2)):
    """Dashed reference lines e ~ h^p, anchored a factor 2 below the coarsest data, labelled O(h^p)."""
    hmin, hmax = min(hs), max(hs)
    if hmin == hmax:
        return
    anchor = min(e for h, e in zip(hs, es) if h == hmax) / 2.0
    for p, ls in zip(orders, ("--", ":")):
        xs = [hmin, hmax]
        ys = [anchor * (x / hmax) ** p for x in xs]
        ax.plot(xs, ys, ls, color="0.45", lw=1.2, label="O(h%s)" % ("" if p == 1 else "$^%d$" % p))


def save(plt, fig, path):
    """The figure as PNG (for report.md) and as PDF beside it, same basename (vector, for papers)."""
    fig.savefig(path)
    fig.savefig(os.path.splitext(path)[0] + ".pdf")
    plt.close(fig)


def magnitude_label(name, pts):
    """|name| where a plotted value is negative: log axes then show magnitudes."""
    return "|%s|" % name if any(p[2] for p in pts) else name


def draw_line(ax, pts, i, label, noisy=None, **kw):
    """One line of line_points() on log-log axes in line i's style. Points of a negative value get open
    markers and noisy ones (noisy(row) true) grey markers, so the plot keeps what log axes would lose."""
    st = style(i)
    ax.loglog([p[0] for p in pts], [p[1] for p in pts], label=label, **st, **kw)
    ms = kw.get("ms", 6)
    for x, y, negative, row in pts:
        grey = bool(noisy and noisy(row))
        if negative or grey:
            edge = "0.6" if grey else st["color"]
            ax.plot([x], [y], ls="none", marker=st["marker"], ms=ms, mec=edge, mfc="white" if negative else edge,
                    zorder=3)


def marker_notes(pts, noisy=None):
    """Legend entries for the marker kinds draw_line used: open (negative value), grey (noisy)."""
    from matplotlib.lines import Line2D
    notes = []
    if any(p[2] for p in pts):
        notes.append(Line2D([], [], ls="none", marker="o", mec="0.3", mfc="white", label="open marker: value < 0"))
    if noisy and any(noisy(p[3]) for p in pts):
        notes.append(Line2D([], [], ls="none", marker="o", mec="0.6", mfc="0.6",
                            label="grey: wall time < %g s: noise" % NOISE_WALL_S))
    return notes


def figure_error_vs_h(plt, groups, metric, title):
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    drawn = []
    for i, (label, g) in enumerate(groups.items()):
        pts = line_points(g, metric, "h")
        if pts:
            draw_line(ax, pts, i, label, lw=1.6, ms=6)
            drawn += pts
    if not drawn:
        plt.close(fig)
        return None
    hs, es = [p[0] for p in drawn], [p[1] for p in drawn]
    reference_slopes(ax, hs, es)
    tidy_log_axis(ax, "x", hs)
    tidy_log_axis(ax, "y")
    ax.set_xlabel("smoothing length h")
    ax.set_ylabel(magnitude_label(metric, drawn))
    ax.set_title(title)
    outside_legend(ax, marker_notes(drawn))
    fig.tight_layout()
    return fig


def figure_metric_vs_h(plt, estimates, metric, title):
    """A time-series metric against h (linear axes, down to h = 0), one line per solver/sweep, each with its
    Richardson estimate at h = 0 (error bar: the GCI uncertainty) and the curve f0 + C h^p through the finest
    run that the estimate assumes. estimates: {label: (points, orders, estimate)} of metric.line_estimates."""
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    drawn = False
    for i, (label, (pts, _, est)) in enumerate(estimates.items()):
        xy = [(h, v) for _, h, v, _ in pts if v is not None and h]
        if not xy:
            continue
        st = style(i)
        ax.plot([h for h, _ in xy], [v for _, v in xy], label=label, lw=1.6, ms=6, **st)
        drawn = True
        if "value" in est:
            f0, p, h1 = est["value"], est["order"], est["h"][0]
            f1 = [v for h, v in xy if h == h1][0]
            hs = [max(h for h, _ in xy) * k / 50.0 for k in range(51)]
            if not est["oscillating"]:  # the curve the extrapolation assumes
                ax.plot(hs, [f0 + (f1 - f0) * (h / h1) ** p for h in hs], ":", color=st["color"], lw=1.0)
            ax.errorbar([0.0], [f0], yerr=[est["uncertainty"]], color=st["color"], marker=st["marker"], mfc="white",
                        capsize=4, ls="none", label="%s, %s: %.4g ± %.2g" % (
                            label, "oscillates, finest" if est["oscillating"] else "h → 0", f0, est["uncertainty"]))
    if not drawn:
        plt.close(fig)
        return None
    ax.set_xlim(left=-0.02 * ax.get_xlim()[1])
    ax.set_xlabel("smoothing length h")
    ax.set_ylabel(metric)
    ax.set_title(title)
    outside_legend(ax)
    fig.tight_layout()
    return fig


def figure_all_errors_vs_h(plt, groups, errors, title):
    n = len(errors)
    if n < 2:
        return None
    cols = 2
    nrows = (n + 1) // 2
    fig, axes = plt.subplots(nrows, cols, figsize=(9, 3.3 * nrows), squeeze=False)
    everything = []
    for k, name in enumerate(errors):
        ax = axes[k // cols][k % cols]
        drawn = []
        for i, (label, g) in enumerate(groups.items()):
            pts = line_points(g, name, "h")
            if pts:
                draw_line(ax, pts, i, label, lw=1.4, ms=5)
                drawn += pts
        if drawn:
            reference_slopes(ax, [p[0] for p in drawn], [p[1] for p in drawn])
            tidy_log_axis(ax, "x", [p[0] for p in drawn])
            tidy_log_axis(ax, "y")
        ax.set_title(magnitude_label(name, drawn))
        ax.set_xlabel("h")
        everything += drawn
    for k in range(n, nrows * cols):
        axes[k // cols][k % cols].axis("off")
    if not everything:
        plt.close(fig)
        return None
    handles, labels = axes[0][0].get_legend_handles_labels()
    handles += marker_notes(everything)
    labels += [h.get_label() for h in handles[len(labels):]]
    fig.suptitle(title)
    fig.legend(handles, labels, loc="lower center", ncol=min(4, len(labels)), frameon=False)
    fig.tight_layout(rect=(0, 0.04 + 0.025 * ((len(labels) - 1) // 4), 1, 1))
    return fig


def noisy_run(row):
    """A run too short for its wall time to measure speed (draw_line greys it)."""
    return noisy_wall(row["wall_time_s"])


def figure_pareto(plt, groups, metric, title):
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    drawn = []
    for i, (label, g) in enumerate(groups.items()):
        pts = line_points(g, metric, "wall_time_s")
        if not pts:
            continue
        draw_line(ax, pts, i, label, noisy=noisy_run, lw=1.6, ms=6)
        drawn += pts
        for t, e, _, r in pts:
            ax.annotate(str(r["nx"]), (t, e), textcoords="offset points", xytext=(5, 4), fontsize=7,
                        color=style(i)["color"])
    if not drawn:
        plt.close(fig)
        return None
    tidy_log_axis(ax, "x")
    tidy_log_axis(ax, "y")
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel(magnitude_label(metric, drawn))
    ax.set_title(title)
    outside_legend(ax, marker_notes(drawn, noisy_run), title="point labels: nx")
    fig.tight_layout()
    return fig


def figure_ksp(plt, groups, title):
    """Linear iterations per time step: the program sums them over a step's pressure solves (projection,
    correction and free-surface passes) and reports only that sum, per step and as its mean and max."""
    fig, ax = plt.subplots(figsize=(7.5, 4.2))
    drawn = False
    Ns = []
    for i, (label, g) in enumerate(groups.items()):
        pts = [(r["N"], r["ksp_iterations_mean"], r["ksp_iterations_max"]) for r in completed(g)
               if r["ksp_iterations_mean"] is not None and r["N"]]
        if not pts:
            continue
        drawn = True
        Ns += [p[0] for p in pts]
        st = style(i)
        ax.semilogx([p[0] for p in pts], [p[1] for p in pts], label=label + " (mean over steps)", lw=1.6, ms=6, **st)
        ax.semilogx([p[0] for p in pts], [p[2] for p in pts], "--", color=st["color"], marker=st["marker"],
                    mfc="none", lw=1, ms=5, label=label + " (max over steps)")
    if not drawn:
        plt.close(fig)
        return None
    ax.set_xlabel("number of particles N")
    ax.set_ylabel("KSP iterations per time step\n(sum over the step's pressure solves)")
    tidy_log_axis(ax, "x", Ns, integer=True)
    ax.set_ylim(0, ax.get_ylim()[1] * 1.1)
    ax.set_title(title)
    outside_legend(ax)
    fig.tight_layout()
    return fig


def read_profile(path):
    """(coordinate, value) columns of a two-column CSV with a header; '#' lines are comments."""
    xs, ys = [], []
    with open(path) as f:
        rows = [l for l in csv.reader(l for l in f if l.strip() and not l.lstrip().startswith("#"))]
    if not rows:
        return xs, ys
    for row in rows[1:]:
        try:
            xs.append(float(row[0]))
            ys.append(float(row[1]))
        except (ValueError, IndexError):
            pass
    return xs, ys


def read_ghia(path, re_number):
    """Coordinate and the column of the given Reynolds number from a Ghia et al. (1982) table."""
    with open(path) as f:
        rows = list(csv.reader(l for l in f if l.strip() and not l.lstrip().startswith("#")))
    header = [h.strip() for h in rows[0]]
    want = [i for i, h in enumerate(header) if re.fullmatch(r"[uv]_Re%d" % re_number, h)]
    if not want:
        return None
    xs, ys = [], []
    for row in rows[1:]:
        xs.append(float(row[0]))
        ys.append(float(row[want[0]]))
    return xs, ys


def reference_file(name):
    """A reference-data file of the lid-driven cavity case (Ghia et al. 1982), or None if absent."""
    p = os.path.join(REPO, "cases", "lid_driven_cavity", "data", name)
    return p if os.path.exists(p) else None


def figure_centrelines(plt, groups, case, study_options, title):
    """Lid-driven cavity: u(0.5, y) and v(x, 0.5) of the finest run of every line against Ghia et al.
    Returns (figure or None, a note for the report or None)."""
    if case != "lid_driven_cavity":
        return None, None
    profiles = []  # (line index, label, u file, v file, row, finest of its line)
    for i, (label, g) in enumerate(groups.items()):
        found = []
        for r in completed(g):
            fu = os.path.join(r["dir"], "centreline_u.csv")
            fv = os.path.join(r["dir"], "centreline_v.csv")
            if os.path.exists(fu) or os.path.exists(fv):
                found.append((i, "%s, nx=%d" % (label, r["nx"]), fu, fv, r))
        profiles += [p + (k == len(found) - 1,) for k, p in enumerate(found)]
    if not profiles:
        return None, "no centreline_u.csv / centreline_v.csv in the run folders"
    re_number = None
    for *_, r, _finest in profiles:
        s = read_json(os.path.join(r["dir"], "summary.json")) or {}
        re_number = (s.get("parameters") or {}).get("re")
        if re_number is not None:
            break
    if re_number is None:
        re_number = study_options.get("re")
    ghia_u = reference_file("ghia1982_u_vertical_centreline.csv")
    ghia_v = reference_file("ghia1982_v_horizontal_centreline.csv")
    ref_u = ref_v = None
    note = None
    if re_number is not None and ghia_u and ghia_v:
        ref_u = read_ghia(ghia_u, int(round(float(re_number))))
        ref_v = read_ghia(ghia_v, int(round(float(re_number))))
        if ref_u is None:
            note = "Ghia et al. have no Re = %s column" % re_number
    else:
        note = "no Ghia et al. reference data (ghia1982_*_centreline.csv) in the repository, or Re unknown"
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.5))
    coarser = False
    for i, label, fu, fv, _, finest in profiles:
        st = dict(color=style(i)["color"], lw=1.6 if finest else 0.9, alpha=1.0 if finest else 0.4,
                  label=label if finest else None)
        coarser = coarser or not finest
        if os.path.exists(fu):
            y, u = read_profile(fu)
            ax1.plot(u, y, "-", **st)
        if os.path.exists(fv):
            x, v = read_profile(fv)
            ax2.plot(x, v, "-", **st)
    if ref_u:
        ax1.plot(ref_u[1], ref_u[0], "ko", mfc="none", ms=5, label="Ghia et al. (1982)")
    if ref_v:
        ax2.plot(ref_v[0], ref_v[1], "ko", mfc="none", ms=5, label="Ghia et al. (1982)")
    ax1.set_xlabel("u(0.5, y)")
    ax1.set_ylabel("y")
    ax2.set_xlabel("x")
    ax2.set_ylabel("v(x, 0.5)")
    ax1.legend()
    ax2.legend()
    fig.suptitle(title + ("" if re_number is None else ", Re = %g" % float(re_number)) +
                 (" (faint: coarser runs)" if coarser else ""))
    fig.tight_layout()
    return fig, note
