"""metric.py and the Richardson estimate of orders.py: the study file's 'metric', reductions of synthetic
time series (exact integrals of known functions), refusals naming what exists, f0 + C h^p recovered to
round-off, and a report of synthetic run folders with ISPH against WCSPH. No runs of the sph program."""

import math
import os
import unittest

from sph_study.collect import collect
from sph_study.metric import check_metric, metric_label, moving_average, parse_metric, reduce_series
from sph_study.orders import richardson, three_grid_order
from sph_study.plan import load_study, plan_runs
from sph_study.report import make_outputs
from sph_study.tests.support import TempDirCase, record_run


def series(f, t0, t1, n):
    """n + 1 equal steps from t0 to t1 (the program's first row is at t = dt, so t0 is usually dt)."""
    t = [t0 + (t1 - t0) * k / n for k in range(n + 1)]
    return t, [f(x) for x in t]


class Parse(unittest.TestCase):
    def test_plain_string_is_a_summary_error(self):
        m = parse_metric("l1_velocity", "s.yaml")
        self.assertEqual(m, {"kind": "summary", "name": "l1_velocity"})
        self.assertEqual(metric_label(m), "l1_velocity")

    def test_column_reduction(self):
        m = parse_metric({"column": "force_baffle_x", "reduce": "integral", "from": 0, "to": "1e0"}, "s.yaml")
        self.assertEqual((m["column"], m["reduce"], m["from"], m["to"], m["order"]),
                         ("force_baffle_x", "integral", 0.0, 1.0, None))
        self.assertEqual(metric_label(m), "integral(force_baffle_x, 0..1)")
        self.assertEqual(metric_label(parse_metric({"column": "x", "reduce": "max"}, "s")), "max(x)")
        self.assertEqual(metric_label(parse_metric({"column": "x", "from": 2}, "s")), "mean(x, 2..end)")

    def test_malformed_metrics_are_refused_in_one_line(self):
        for value, msg in [
                ({"column": "x", "reduce": "median"}, "s.yaml: metric: reduce 'median' is not one of mean, rms, max, "
                                                      "min, integral, period, amplitude"),
                ({"column": "x", "window": 1}, "s.yaml: metric: unknown key(s) window (known: column, from, order, "
                                               "reduce, smooth, to)"),
                ({"column": "x", "smooth": -1}, "s.yaml: metric: 'smooth' (the moving average's width in time) "
                                                "must be >= 0"),
                ({"reduce": "mean"}, "s.yaml: metric: 'column' must name a timeseries.csv column, e.g. force_baffle_x"),
                ({"column": "x", "from": 1, "to": 1}, "s.yaml: metric: 'to' (1) must be after 'from' (1)"),
                ({"column": "x", "to": "soon"}, "s.yaml: metric: 'to' must be a number, got 'soon'"),
                ({"column": "x", "order": 0}, "s.yaml: metric: 'order' (the order assumed with two resolutions) "
                                              "must be > 0"),
                (3, "s.yaml: 'metric' must be an error name of summary.json (e.g. l1_velocity) or {column: NAME, "
                    "reduce: mean|rms|max|min|integral|period|amplitude, from: T0, to: T1}")]:
            with self.assertRaises(ValueError) as cm:
                parse_metric(value, "s.yaml")
            self.assertEqual(str(cm.exception), msg)


class Reductions(unittest.TestCase):
    def test_integral_of_a_linear_function_is_exact_on_uneven_steps(self):
        t = [0.01, 0.03, 0.1, 0.35, 0.4, 0.8, 1.0, 1.2]
        f = [3 * x + 1 for x in t]
        # from 0.05 to 0.9: ends interpolated inside the series; exact: 1.5 (0.9² - 0.05²) + 0.85
        self.assertAlmostEqual(reduce_series(t, f, "integral", 0.05, 0.9), 1.5 * (0.81 - 0.0025) + 0.85, places=13)
        self.assertAlmostEqual(reduce_series(t, f, "mean", 0.05, 0.9), (1.5 * (0.81 - 0.0025) + 0.85) / 0.85,
                               places=13)
        self.assertAlmostEqual(reduce_series(t, f, "max", 0.05, 0.9), 3.7, places=13)
        self.assertAlmostEqual(reduce_series(t, f, "min", 0.05, 0.9), 1.15, places=13)

    def test_series_starting_one_step_late_holds_its_first_value(self):
        # the program's first row is at t = dt: a constant's integral from 0 is still exact
        t, f = series(lambda x: 2.0, 0.01, 1.0, 99)
        self.assertAlmostEqual(reduce_series(t, f, "integral", 0, 1), 2.0, places=13)
        self.assertAlmostEqual(reduce_series(t, f, "integral"), 2.0, places=13)

    def test_a_first_step_longer_than_the_rest_is_held(self):
        # a flow starting from rest: the first step (to the first row) is the longest
        t = [9.1e-5] + [9.1e-5 + 8.9e-5 * k for k in range(1, 100)]
        self.assertAlmostEqual(reduce_series(t, [4.0] * len(t), "integral", 0, t[-1]), 4.0 * t[-1], places=12)

    def test_sine_over_whole_periods(self):
        # equal steps over whole periods: the trapezoid integrates sin and sin² exactly
        t, f = series(lambda x: 5 + 3 * math.sin(2 * math.pi * x / 0.25), 0.0, 1.0, 400)
        self.assertAlmostEqual(reduce_series(t, f, "integral", 0, 1), 5.0, places=12)
        self.assertAlmostEqual(reduce_series(t, f, "mean", 0, 1), 5.0, places=12)
        t, f = series(lambda x: 3 * math.sin(2 * math.pi * x / 0.25), 0.0, 1.0, 400)
        self.assertAlmostEqual(reduce_series(t, f, "rms", 0, 1), 3 / math.sqrt(2), places=12)

    def test_period_and_amplitude(self):
        t, f = series(lambda x: 0.5 + 3 * math.sin(2 * math.pi * x / 0.4 + 0.3), 0.0, 2.0, 4000)
        self.assertAlmostEqual(reduce_series(t, f, "period", 0, 2), 0.4, places=6)
        self.assertAlmostEqual(reduce_series(t, f, "amplitude", 0, 2), 3.0, places=5)
        with self.assertRaisesRegex(ValueError, "fewer than two upward crossings"):
            reduce_series(t, f, "period", 0, 0.3)

    def test_window_beyond_the_run_is_refused(self):
        t, f = series(lambda x: x, 0.01, 0.3, 29)
        with self.assertRaisesRegex(ValueError, r"the run covers t = 0.01 to 0.3 only, not 0 to 1"):
            reduce_series(t, f, "integral", 0, 1)


class MovingAverage(unittest.TestCase):
    def test_a_sine_is_damped_by_its_sinc(self):
        # the mean of sin(w t) over [t - W/2, t + W/2] is sin(w t) sin(w W/2) / (w W/2); uneven steps
        w, width = 2 * math.pi / 0.07, 0.05
        t = [0.0]
        while t[-1] < 1:
            t.append(t[-1] + (2e-4 if len(t) % 2 else 3e-4))
        g = moving_average(t, [2 + math.sin(w * x) for x in t], width)
        factor = math.sin(w * width / 2) / (w * width / 2)
        for k in range(0, len(t), 97):
            if width / 2 <= t[k] <= t[-1] - width / 2:
                self.assertAlmostEqual(g[k], 2 + factor * math.sin(w * t[k]), delta=2e-4)

    def test_a_linear_function_is_kept_and_a_period_averages_out(self):
        t, f = series(lambda x: 3 * x - 1 + math.cos(2 * math.pi * x / 0.05), 0.0, 1.0, 5000)
        g = moving_average(t, f, 0.05)
        inside = [k for k, x in enumerate(t) if 0.025 <= x <= 0.975]
        self.assertLess(max(abs(g[k] - (3 * t[k] - 1)) for k in inside), 1e-5)
        # at the ends the window is cut to the series: a linear function's mean over [0, W/2] is at W/4
        g = moving_average(*series(lambda x: 3 * x, 0.0, 1.0, 100), 0.2)
        self.assertAlmostEqual(g[0], 3 * 0.05, places=12)
        self.assertAlmostEqual(g[-1], 3 * 0.95, places=12)

    def test_a_smoothed_metric_reads_the_average_not_the_spikes(self):
        m = parse_metric({"column": "force_baffle_x", "reduce": "max", "to": 1, "smooth": 0.1}, "s.yaml")
        self.assertEqual(metric_label(m), "max(force_baffle_x, 0..1, smoothed 0.1)")
        t, f = series(lambda x: 1.0, 0.0, 1.0, 1000)
        f[500] = 101.0  # one step's spike: its mean over 0.1 is 100 * 1e-3 / 0.1 = 1
        g = moving_average(t, f, 0.1)
        self.assertAlmostEqual(reduce_series(t, g, "max", 0, 1), 2.0, places=9)
        self.assertAlmostEqual(reduce_series(t, f, "max", 0, 1), 101.0, places=12)


class Richardson(unittest.TestCase):
    F0, C = 2.5, -0.7

    def f(self, h, p):
        return self.F0 + self.C * h ** p

    def test_recovers_f0_and_p_for_any_refinement_ratios(self):
        for hs in ([0.1, 0.05, 0.025], [0.1, 0.06, 0.025], [0.3, 0.17, 0.04], [0.2, 0.1, 0.05, 0.025]):
            for p in (0.8, 1.0, 1.6, 2.0, 3.0):
                est = richardson(hs, [self.f(h, p) for h in hs])
                self.assertAlmostEqual(est["order"], p, delta=1e-10 * p, msg=(hs, p))
                self.assertAlmostEqual(est["value"], self.F0, delta=1e-12 * self.F0, msg=(hs, p))
                self.assertTrue(est["observed"])
                self.assertEqual(est["safety"], 1.25)
                h1, h2 = sorted(hs)[:2]
                unc = 1.25 * abs(self.f(h1, p) - self.f(h2, p)) / ((h2 / h1) ** p - 1)
                self.assertAlmostEqual(est["uncertainty"], unc, delta=1e-12)
                self.assertAlmostEqual(est["gci"], unc / abs(self.f(h1, p)), delta=1e-12)

    def test_three_grid_order_alone(self):
        p, s = three_grid_order((0.025, 0.06, 0.1), [self.f(h, 1.7) for h in (0.025, 0.06, 0.1)])
        self.assertAlmostEqual(p, 1.7, places=12)
        self.assertEqual(s, 1)

    def test_two_grids_use_the_assumed_order_and_factor_3(self):
        est = richardson([0.1, 0.05], [self.f(0.1, 2), self.f(0.05, 2)], assumed_order=2)
        self.assertAlmostEqual(est["value"], self.F0, places=13)
        self.assertEqual((est["observed"], est["safety"], est["order"]), (False, 3.0, 2.0))
        self.assertAlmostEqual(est["uncertainty"], 3 * abs(self.C) * (0.01 - 0.0025) / 3, places=13)
        self.assertIn("reason", richardson([0.1, 0.05], [1.0, 2.0]))

    def test_oscillating_and_diverging_values(self):
        est = richardson([0.1, 0.05, 0.025], [1.0, 1.4, 1.2])
        self.assertTrue(est["oscillating"])
        self.assertEqual((est["value"], est["safety"]), (1.2, None))
        self.assertAlmostEqual(est["uncertainty"], 0.2, places=13)
        est = richardson([0.1, 0.05, 0.025], [1.0, 1.1, 1.3])
        self.assertEqual(est["reason"], "the differences grow with refinement (order -1.00): not converging")
        self.assertIn("reason", richardson([0.1, 0.05, 0.025], [1.0, 1.0, 1.0]))
        self.assertIn("reason", richardson([0.1], [1.0]))


def load_study_text(case, metric_line):
    return load_study(case.write("s.yaml", "name: s\ncase: scene\noptions: {scene_file: scene.yaml}\n"
                                 "solvers: [isph, wcsph]\nresolutions: [10, 20, 40]\n" + metric_line))


class LoadBad(TempDirCase):
    def test_study_file_with_a_bad_metric_exits(self):
        with self.assertRaises(SystemExit) as cm:
            load_study_text(self, "metric: {column: x, reduce: median}\n")
        self.assertIn("metric: reduce 'median' is not one of", str(cm.exception))


HEADER = "step,t,dt,kinetic_energy,force_baffle_x,force_baffle_y\n"
# Impulse over 0..1 of the runs below: f0 + C h^p with f0 = 40, C = 300; ISPH p = 2, WCSPH p = 1.
F0, C = 40.0, 300.0
P = {"isph": 2.0, "wcsph": 1.0}


def write_run(run, h):
    """A completed run whose force_baffle_x is the constant that makes its impulse over 0..1 f0 + C h^p."""
    impulse = F0 + C * h ** P[run["solver"]]
    record_run(run, summary={"status": "completed", "n_particles": 100, "kernel": {"h": h}, "steps": 100,
                             "wall_time_s": 2.0, "errors": {}})
    with open(os.path.join(run["dir"], "timeseries.csv"), "w") as f:
        f.write(HEADER)
        for k in range(1, 101):
            f.write("%d,%r,0.01,0,%r,0\n" % (k, 0.01 * k, impulse))


class Report(TempDirCase):
    def make(self, metric_line, resolutions="[10, 20, 40]"):
        path = self.write("s.yaml", "name: s\ncase: scene\noptions: {scene_file: scene.yaml}\nsolvers: [isph, wcsph]\n"
                                    "resolutions: %s\n%s" % (resolutions, metric_line))
        study = load_study(path)
        out = os.path.join(self.tmp, "out")
        runs = plan_runs(study, out, "/opt/sph", 0)
        for r in runs:
            write_run(r, 1.5 / r["nx"])
        make_outputs(study, path, runs, out, (0, len(runs), 0), 1, 0)
        with open(os.path.join(out, "report.md")) as f:
            return f.read(), out, runs

    def test_richardson_per_scheme_and_one_table(self):
        text, out, _ = self.make("metric: {column: force_baffle_x, reduce: integral, from: 0, to: 1}\n")
        self.assertIn("## Metric `integral(force_baffle_x, 0..1)`", text)
        self.assertIn("Metric: the time integral (trapezoid over the steps) of `force_baffle_x` over 0 ≤ t ≤ 1", text)
        self.assertIn("| 40 | 0.0375 | 40.4219 | -1.26562 | 2.00 |", text)  # ISPH: 40 + 300 h², h = 1.5/nx
        self.assertIn("Richardson estimate: 40 ± 0.53 (GCI 1.3 %, observed order 2.00, factor of safety 1.25).", text)
        self.assertIn("### isph and wcsph against each other", text)
        self.assertIn("| observed order (finest three) | 2.00 | 1.00 |", text)
        self.assertIn("| Richardson estimate (h → 0) | 40 | 40 |", text)
        self.assertRegex(text, "The estimates of `isph` and `wcsph` are [0-9.e-]+ apart: within the sum")
        self.assertIn("no speed-against-accuracy table", text)
        self.assertNotIn("## Observed orders (finest pair", text)
        with open(os.path.join(out, "results.csv")) as f:
            lines = f.read().splitlines()
        self.assertTrue(lines[0].endswith(",integral(force_baffle_x, 0..1),run_dir") or
                        lines[0].endswith(',"integral(force_baffle_x, 0..1)",run_dir'), lines[0])
        if os.path.exists(os.path.join(out, "error_vs_h.png")) or "## Plots" in text:
            self.assertIn("![integral(force_baffle_x, 0..1) against h, extrapolated to h → 0](metric_vs_h.png)", text)
            self.assertTrue(os.path.exists(os.path.join(out, "metric_vs_h.pdf")))

    def test_two_resolutions_assume_an_order(self):
        text, _, _ = self.make("metric: {column: force_baffle_x, reduce: integral, order: 2}\n", "[20, 40]")
        self.assertIn("Richardson estimate: 40 ± 1.3 (GCI 3.1 %, assumed order 2.00, factor of safety 3).", text)
        self.assertIn("| observed order (finest three) | – (assumed 2) | – (assumed 2) |", text)

    def test_unknown_column_is_refused_naming_the_columns(self):
        with self.assertRaises(SystemExit) as cm:
            self.make("metric: {column: force_bafle_x, reduce: max}\n")
        self.assertEqual(str(cm.exception), "study: metric column 'force_bafle_x' is not in timeseries.csv; its "
                         "columns: dt, kinetic_energy, force_baffle_x, force_baffle_y")

    def test_column_named_as_a_plain_metric_is_refused_with_the_syntax(self):
        with self.assertRaises(SystemExit) as cm:
            self.make("metric: force_baffle_x\n")
        self.assertEqual(str(cm.exception), "study: metric 'force_baffle_x' is not an error of the runs (a "
                         "timeseries.csv column: metric: {column: force_baffle_x, reduce: mean|integral|..., from: T0, "
                         "to: T1}); their errors: none (no reference solution); timeseries.csv columns: dt, "
                         "kinetic_energy, force_baffle_x, force_baffle_y")

    def test_default_metric_of_a_scene_is_not_refused(self):
        text, _, _ = self.make("")
        self.assertIn("The runs report no error norm", text)


class Check(TempDirCase):
    def test_check_metric(self):
        run = {"dir": os.path.join(self.tmp, "r"), "args": [], "mpi": 0, "solver": "isph"}
        write_run(run, 0.1)
        self.assertIsNone(check_metric(parse_metric({"column": "force_baffle_y"}, "s"), run["dir"]))
        self.assertIn("its columns: dt,", check_metric(parse_metric({"column": "t"}, "s"), run["dir"]))
        self.assertEqual(collect([dict(run, label="isph", sweep={}, nx=10)])[0]["status"], "completed")


if __name__ == "__main__":
    unittest.main()
