"""collect.py, report.py (and plots.py through make_outputs): rows from synthetic run folders, results.csv,
the orders and the speed table of report.md. No runs of the sph program."""

import contextlib
import csv
import importlib.util
import io
import os
import unittest

from sph_study.collect import collect, completed, error_names, groups_of, line_points, write_csv
from sph_study.orders import pareto_table
from sph_study.plan import load_study, plan_runs
from sph_study.report import flag_noise, fmt, fmt_time, fmt_wall, make_outputs, md_table, write_report
from sph_study.tests.support import TempDirCase, record_run

STUDY = """\
name: synthetic
case: taylor_green
solvers: [isph, wcsph]
resolutions: [40, 10, 20]
options: {re: 100, t_end: 1}
solver_options: {wcsph: {delta: 0.1}}
solver_resolution_options:
  wcsph: {c0_factor: [40, 10, 20]}
metric: l1_velocity
"""
H = {10: 0.1, 20: 0.05, 40: 0.025}
# ISPH: l1 ~ h^2 (order 2), linf ~ h (order 1), e = 0.04 / t.  WCSPH: l1 ~ h (order 1), e = 0.02 / t; nx 40 fails.
ISPH = {10: (1.0, 4e-2, 1e-1), 20: (4.0, 1e-2, 5e-2), 40: (16.0, 2.5e-3, 2.5e-2)}
WCSPH = {10: (0.5, 4e-2, 2e-1), 20: (1.0, 2e-2, 1e-1)}


def summary(nx, t, l1, linf, ksp=None):
    s = {"status": "completed", "n_particles": nx * nx, "kernel": {"h": H[nx]}, "steps": 10 * nx,
         "wall_time_s": t, "time_per_particle_step_s": t / (nx * nx * 10 * nx),
         "errors": {"l1_velocity": l1, "linf_velocity": linf}}
    if ksp:
        s["ksp"] = {"iterations_mean": ksp, "iterations_max": int(ksp) + 2}
    return s


class SyntheticStudy(TempDirCase):
    """The study above with its run folders filled in as the program and execute() would leave them."""

    def setUp(self):
        super().setUp()
        self.study_file = self.write("synthetic.yaml", STUDY)
        self.study = load_study(self.study_file)
        self.out = os.path.join(self.tmp, "out")
        self.runs = plan_runs(self.study, self.out, "/opt/sph", 0)
        for r in self.runs:
            rec = {"busy_cores_at_start": 0.1, "cpus": 4}
            if r["solver"] == "isph":
                t, l1, linf = ISPH[r["nx"]]
                record_run(r, summary=summary(r["nx"], t, l1, linf, ksp=5.0 + r["nx"] / 10), **rec)
            elif r["nx"] in WCSPH:
                record_run(r, summary=summary(r["nx"], *WCSPH[r["nx"]]), **rec)
            else:
                record_run(r, status="failed", failure="step 3 (t = 0.1): non-finite velocity", **rec)
        self.rows = collect(self.runs)

    def report(self, rows=None, pareto=None, counts=(6, 0, 1), jobs=1, mpi=0, notes=()):
        rows = self.rows if rows is None else rows
        groups = groups_of(rows)
        errors = error_names(rows)
        if pareto is None:
            lines = {k: [(r["wall_time_s"], r["errors"]["l1_velocity"]) for r in completed(g)] for k, g in groups.items()}
            pareto = pareto_table(lines, [2e-2, 1e-2, 1e-4])
        path = os.path.join(self.out, "report.md")
        write_report(path, self.study, self.study_file, rows, groups, errors, "l1_velocity", [], pareto, counts,
                     jobs, mpi, list(notes))
        with open(path) as f:
            return f.read()


class Collect(SyntheticStudy):
    def test_rows(self):
        self.assertEqual([(r["solver"], r["nx"], r["status"]) for r in self.rows],
                         [("isph", 10, "completed"), ("isph", 20, "completed"), ("isph", 40, "completed"),
                          ("wcsph", 10, "completed"), ("wcsph", 20, "completed"), ("wcsph", 40, "failed")])
        isph20 = self.rows[1]
        self.assertEqual((isph20["N"], isph20["h"], isph20["steps"], isph20["wall_time_s"]), (400, 0.05, 200, 4.0))
        self.assertEqual((isph20["ksp_iterations_mean"], isph20["ksp_iterations_max"]), (7.0, 9))
        self.assertEqual((isph20["load"], isph20["cpus"]), (0.1, 4))
        wcsph40 = self.rows[-1]
        self.assertEqual((wcsph40["failure"], wcsph40["errors"], wcsph40["N"]),
                         ("step 3 (t = 0.1): non-finite velocity", {}, None))
        self.assertIsNone(self.rows[3]["ksp_iterations_mean"])
        self.assertEqual(error_names(self.rows), ["l1_velocity", "linf_velocity"])

    def test_a_run_never_made(self):
        run = dict(self.runs[0], dir=os.path.join(self.tmp, "nothing"))
        row = collect([run])[0]
        self.assertEqual((row["status"], row["failure"], row["errors"]), ("not run", "", {}))

    def test_groups_and_points(self):
        groups = groups_of(list(reversed(self.rows)))
        self.assertEqual(list(groups), ["wcsph", "isph"])
        self.assertEqual([r["nx"] for r in groups["isph"]], [10, 20, 40])
        self.assertEqual([p[:3] for p in line_points(groups["wcsph"], "l1_velocity", "h")],
                         [(0.1, 4e-2, False), (0.05, 2e-2, False)])
        self.assertEqual([p[3]["nx"] for p in line_points(groups["wcsph"], "l1_velocity", "h")], [10, 20])
        self.assertEqual(line_points(groups["isph"], "nothing", "h"), [])
        self.assertEqual(len(completed(self.rows)), 5)

    def test_results_csv(self):
        path = os.path.join(self.out, "results.csv")
        write_csv(path, self.rows, ["cfl"], error_names(self.rows))
        with open(path) as f:
            rows = list(csv.reader(f))
        self.assertEqual(rows[0], ["cfl", "solver", "nx", "N", "h", "steps", "wall_time_s", "time_per_particle_step_s",
                                   "ksp_iterations_mean", "ksp_iterations_max", "status", "failure",
                                   "steady_state_reached", "l1_velocity", "linf_velocity", "run_dir"])
        self.assertEqual(rows[2][:6] + rows[2][8:], ["", "isph", "20", "400", "0.05", "200", "7.0", "9", "completed",
                                                      "", "", "0.01", "0.05", "isph-nx20"])
        self.assertEqual(rows[-1], ["", "wcsph", "40", "", "", "", "", "", "", "", "failed",
                                    "step 3 (t = 0.1): non-finite velocity", "", "", "", "wcsph-nx40"])


class Report(SyntheticStudy):
    def test_header_and_options(self):
        text = self.report()
        self.assertTrue(text.startswith("# Study `synthetic`\n\nCase `taylor_green`, solvers `isph`, `wcsph`, "
                                        "resolutions nx = 10, 20, 40. Study file `%s`; generated " % self.study_file))
        self.assertIn("\nFixed options: `-re 100` `-t_end 1`.\n", text)
        self.assertIn("\nOptions of `wcsph` only: `-delta 0.1`.\n", text)
        self.assertIn("\nOptions refined with h (`wcsph`): `-c0_factor` 10, 20, 40 at nx = 10, 20, 40.\n", text)
        self.assertIn("Runs: 6 in all, 5 completed, 1 failed (the last invocation ran 6 and found 0 up to date).", text)
        self.assertNotIn("Note:", text)

    def test_observed_orders(self):
        text = self.report()
        self.assertIn("| solver / sweep | nx pair | l1_velocity | linf_velocity |\n|---|---:|---:|---:|\n"
                      "| isph | 20→40 | 2.00 | 1.00 |\n| wcsph | 10→20 | 1.00 | 1.00 |\n", text)
        # per run: the order in the row of the finer run
        self.assertIn("| 40 | completed | – | 1600 | 0.025 | 400 | 16 | 2.5e-05 | 9.0 / 11 | 2.500e-03 | 2.00 | "
                      "2.500e-02 | 1.00 |", text)
        self.assertIn("| 10 | completed | – | 100 | 0.1 | 100 | 0.5† | 5e-05† | 4.000e-02 |  | 2.000e-01 |  |", text)
        self.assertIn("| 40 | **failed** | – |  |  |  |  |  | step 3 (t = 0.1): non-finite velocity |  |  |  |", text)
        self.assertNotIn("Remarks on", text)

    def test_failed_runs(self):
        self.assertIn("## Failed runs\n\n- `wcsph` nx=40: step 3 (t = 0.1): non-finite velocity (folder `wcsph-nx40`)\n",
                      self.report())

    def test_speed_table(self):
        text = self.report()
        self.assertIn("| l1_velocity ≤ | isph | wcsph | fastest | speed-up vs next |\n|---|---:|---:|---:|---:|\n"
                      "| 0.02 | 2 s | 1 s | wcsph | 2.00× |\n| 0.01 | 4 s | – | isph |  |\n"
                      "| 0.0001 | – | – | none |  |\n", text)
        self.assertIn("- `l1_velocity` ≤ 0.02: **wcsph** is ahead (1 s against 2 s for isph, 2.00× faster).\n"
                      "- `l1_velocity` ≤ 0.01: only **isph** reaches it (4 s).\n"
                      "- `l1_velocity` ≤ 0.0001: no run reached it.\n", text)

    def test_wall_times_under_1_s_are_flagged_not_dropped(self):
        text = self.report()
        # wcsph nx 10 ran 0.5 s: its wall time and time per particle-step are kept, marked, with a footnote
        self.assertIn("| 10 | completed | – | 100 | 0.1 | 100 | 0.5† | 5e-05† |", text)
        self.assertIn("| 20 | completed | – | 400 | 0.05 | 200 | 1 | 1.25e-05 |", text)
        self.assertEqual(text.count("\n† wall time < 1 s: timer noise, not a measure of speed.\n"), 1)
        # a speed-table time under 1 s: marked there too, with the table's own footnote
        pareto = pareto_table({"isph": [(0.4, 4e-2), (4.0, 1e-2)], "wcsph": [(2.0, 4e-2)]}, [4e-2, 1e-2])
        text = self.report(pareto=pareto)
        self.assertIn("| 0.04 | ≤ 0.4 s† | ≤ 2 s | isph | 5.00× |", text)
        self.assertIn("**isph** is ahead (0.4 s† against 2 s for wcsph, 5.00× faster).", text)
        self.assertEqual(text.count("\n† wall time < 1 s: timer noise, not a measure of speed.\n"), 2)

    def test_no_noise_footnote_without_short_runs(self):
        for r in self.rows:
            if r["wall_time_s"] is not None:
                r["wall_time_s"] += 1.0
        self.assertNotIn("†", self.report())

    def test_no_speed_table_without_completed_runs(self):
        self.assertIn("No completed runs with the metric `l1_velocity` and a wall time.", self.report(pareto=[]))

    def test_runs_without_error_norms_say_so(self):
        # A scene's runs (no reference solution) report no norm: the report names no metric for them.
        rows = [dict(r, errors={}) for r in self.rows]
        text = self.report(rows=rows, pareto=[])
        self.assertIn("The runs report no error norm (a scene has no reference solution)", text)
        self.assertNotIn("Error metric of the plots", text)
        self.assertIn("Error metric of the plots and the speed comparison: `l1_velocity`.", self.report())

    def test_remarks_on_growing_and_stagnating_errors(self):
        for r in self.rows:
            if r["solver"] == "isph" and r["nx"] == 20:
                r["errors"]["l1_velocity"] = 5e-2          # grows from nx 10 to 20
            if r["solver"] == "isph" and r["nx"] == 40:
                r["errors"]["l1_velocity"] = 4.5e-2        # order 0.15 between 20 and 40
        text = self.report()
        self.assertIn("Remarks on `l1_velocity`:\n\n"
                      "- `isph`: `l1_velocity` grows from nx=10 to nx=20 (0.04 → 0.05).\n"
                      "- `isph`: `l1_velocity` stagnates between nx=20 and nx=40 (order 0.15): an error floor "
                      "independent of h dominates there.\n", text)

    def test_busy_cores_note(self):
        for r in self.rows:
            r["load"] = 1.5
        self.assertIn("Note: all 6 runs started while other work kept up to 1.5 of the 4 cores busy: wall times may "
                      "be inflated.", self.report())
        self.rows[0]["load"] = 0.0
        self.assertIn("Note: isph nx=20; isph nx=40; wcsph nx=10; wcsph nx=20; wcsph nx=40 started", self.report())

    def test_parallel_runs_and_mpi(self):
        text = self.report(jobs=2, mpi=3, notes=["a note"])
        self.assertIn("by `scripts/study` with `-j 2`. MPI ranks per run: 3.", text)
        self.assertIn("Note: runs were made 2 at a time, so wall times include contention for the cores.", text)
        self.assertIn("## Notes\n\n- a note\n", text)

    def test_study_file_in_the_repository_is_named_relative_to_it(self):
        from sph_study.common import REPO
        self.study_file = os.path.join(REPO, "cases", "studies", "synthetic.yaml")
        self.assertIn("Study file `cases/studies/synthetic.yaml`;", self.report())


class Formats(unittest.TestCase):
    def test_fmt(self):
        self.assertEqual([fmt(None), fmt(""), fmt(0.123456), fmt(3), fmt(2.5e-3, "%.3e"), fmt("x")],
                         ["", "", "0.1235", "3", "2.500e-03", "x"])

    def test_fmt_time(self):
        self.assertEqual([fmt_time(None), fmt_time(0.0344), fmt_time(9.99), fmt_time(123.4)],
                         ["–", "0.0344 s", "9.99 s", "123 s"])

    def test_fmt_wall_marks_noise(self):
        self.assertEqual([fmt_wall(None), fmt_wall(0.0344), fmt_wall(1.0), fmt_wall(123.4)],
                         ["–", "0.0344 s†", "1 s", "123 s"])
        self.assertEqual([flag_noise(0.5, ""), flag_noise(0.5, "0.5"), flag_noise(None, "x")], ["", "0.5†", "x"])

    def test_md_table(self):
        self.assertEqual(md_table(["a", "b"], [[1, 2]]), "| a | b |\n|---|---:|\n| 1 | 2 |")
        self.assertEqual(md_table(["a"], [], align=["---"]), "| a |\n|---|")


class MakeOutputs(SyntheticStudy):
    def test_tables_plots_and_report(self):
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            rows = make_outputs(self.study, self.study_file, self.runs, self.out, (0, 6, 0), 1, 0)
        self.assertEqual(len(rows), 6)
        self.assertEqual(err.getvalue(), "")
        plots = (["error_vs_h.png", "errors_vs_h.png", "pareto.png", "ksp_iterations.png"]
                 if importlib.util.find_spec("matplotlib") else [])
        pdfs = [os.path.splitext(f)[0] + ".pdf" for f in plots]  # every figure also as PDF, same basename
        for f in ["results.csv", "report.md"] + plots + pdfs:
            self.assertGreater(os.path.getsize(os.path.join(self.out, f)), 0, f)
        for f in pdfs:
            with open(os.path.join(self.out, f), "rb") as pdf:
                self.assertEqual(pdf.read(5), b"%PDF-", f)
        for f in ("centrelines.png", "centrelines.pdf"):  # not a cavity study
            self.assertFalse(os.path.exists(os.path.join(self.out, f)))
        with open(os.path.join(self.out, "report.md")) as f:
            text = f.read()
        for title, fname in (("l1_velocity against h", "error_vs_h.png"), ("Every error norm against h", "errors_vs_h.png"),
                             ("l1_velocity against wall time (speed–accuracy)", "pareto.png"),
                             ("KSP iterations per time step against N", "ksp_iterations.png")):
            if plots:
                pdf = fname.replace(".png", ".pdf")
                self.assertIn("### %s\n\n![%s](%s)\n\nVector version: [%s](%s).\n" % (title, title, fname, pdf, pdf),
                              text)
        # automatic levels: 1-2-5 values between the smallest error and the largest coarsest-run error
        self.assertIn("| 0.02 | 2 s | 1 s | wcsph | 2.00× |", text)

    def test_unknown_metric_named_in_the_study_is_refused(self):
        self.study["metric"] = "l2_nothing"
        with self.assertRaises(SystemExit) as cm:
            make_outputs(self.study, self.study_file, self.runs, self.out, (0, 6, 0), 1, 0)
        self.assertEqual(str(cm.exception), "study: metric 'l2_nothing' is not an error of the runs; their errors: "
                         "l1_velocity, linf_velocity")

    def test_unknown_default_metric_falls_back_to_the_first_error(self):
        self.study["metric"] = "l2_nothing"
        self.study["metric_given"] = False
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            make_outputs(self.study, self.study_file, self.runs, self.out, (0, 6, 0), 1, 0)
        self.assertEqual(err.getvalue(), "study: metric l2_nothing not found; using l1_velocity\n")
        with open(os.path.join(self.out, "report.md")) as f:
            self.assertIn("- metric `l2_nothing` is not among the errors of the runs (l1_velocity, linf_velocity); "
                          "using `l1_velocity`", f.read())


if __name__ == "__main__":
    unittest.main()
