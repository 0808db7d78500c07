"""matrix.py: failure reasons, the classification of cells, matrix.csv and matrix.md, from synthetic run
folders (no runs of the sph program)."""

import csv
import os
import unittest

from sph_study.execute import make_scene
from sph_study.matrix import (cell_text, classify_cell, energy_cell_text, energy_figures, make_matrix_outputs,
                              option_problem, short_reason)
from sph_study.plan import load_study, plan_matrix_runs
from sph_study.tests.support import TempDirCase, record_run

GAS = "this case is a compressible gas (ideal-gas EOS, energy equation): use -solver compressible, not isph"

MATRIX = """\
name: mini
description: A 2 x 3 matrix.
matrix:
  rows:
    - {label: TGV, case: taylor_green, options: {nx: 8}, metric: l1_velocity}
    - {label: Sod, case: sod, options: {nx: 48}, metric: l1_density}
  columns:
    - {label: ISPH, solver: isph}
    - {label: WCSPH, solver: wcsph, options: {density_diffusion: none}}
    - {label: gas, solver: compressible}
"""


class Reasons(unittest.TestCase):
    def test_short_reason(self):
        self.assertEqual(short_reason("step 12 (t = 0.034): non-finite velocity at particle 7"),
                         "non-finite velocity at particle 7")
        self.assertEqual(len(short_reason("x" * 100)), 61)
        self.assertEqual(short_reason("x" * 100), "x" * 60 + "…")
        self.assertEqual(short_reason("a\nb"), "a b")
        self.assertEqual(short_reason(None), "")

    def test_option_problem(self):
        self.assertTrue(option_problem("-cfl must be in (0, 1] (got 5)"))
        self.assertTrue(option_problem("unknown Option -foo"))
        self.assertFalse(option_problem(GAS))
        self.assertFalse(option_problem(None))


class Cells(TempDirCase):
    def setUp(self):
        super().setUp()
        self.study = load_study(self.write("mini.yaml", MATRIX))
        self.out = os.path.join(self.tmp, "m")
        self.runs = {(r["row"], r["column"]): r for r in plan_matrix_runs(self.study, self.out, "/opt/sph", 0)}

    def test_not_run(self):
        c = classify_cell(self.runs["TGV", "ISPH"])
        self.assertEqual(c, ("not run", "", "l1_velocity", None, None, None))
        self.assertEqual(cell_text(c), "not run")

    def test_ok(self):
        run = self.runs["TGV", "ISPH"]
        record_run(run, summary={"status": "completed", "errors": {"l1_velocity": 0.0123, "linf_velocity": 1.0},
                                 "wall_time_s": 2.0, "steps": 5}, elapsed_s=3.0)
        c = classify_cell(run)
        self.assertEqual(c, ("ok", "", "l1_velocity", 0.0123, 2.0, 5))
        self.assertEqual(cell_text(c), "ok, l1_velocity=0.0123 (2 s)")

    def test_energy_created(self):
        # Pressure +2 and shifting +1 created, viscous -3 took out: 3 of the scale 10 (gravity's kinetic
        # energy, the largest), said in the cell before its wall time.
        run = self.runs["TGV", "ISPH"]
        budget = {"kinetic_energy_start": 0.0, "kinetic_energy_end": 4.0, "gravity_released": 10.0,
                  "work": {"pressure": 2.0, "shifting": 1.0, "viscous": -3.0, "gravity": 0.5}}
        record_run(run, summary={"status": "completed", "errors": {"l1_velocity": 0.0123}, "wall_time_s": 2.0,
                                 "steps": 5, "conservation": {"energy_budget": budget}}, elapsed_s=3.0)
        self.assertEqual(energy_figures(run), (3.0, 10.0))
        self.assertEqual(energy_cell_text(run, classify_cell(run)), "ok, l1_velocity=0.0123, energy +30 % (2 s)")
        other = self.runs["TGV", "WCSPH"]
        record_run(other, summary={"status": "completed", "errors": {"l1_velocity": 0.01}, "wall_time_s": 2.0})
        self.assertIsNone(energy_figures(other))
        self.assertEqual(energy_cell_text(other, classify_cell(other)), "ok, l1_velocity=0.01 (2 s)")

    def test_ok_but_not_measured(self):
        run = self.runs["TGV", "ISPH"]
        record_run(run, summary={"errors": {"l1_velocity": None}, "errors_unmeasured": {"l1_velocity": "why"}},
                   elapsed_s=0.5)
        c = classify_cell(run)
        self.assertEqual(c, ("ok", "not measured: why", "l1_velocity", None, 0.5, None))
        self.assertEqual(cell_text(c), "ok (not measured: why) (0.5 s†)")  # under 1 s: marked as noise

    def test_ok_without_the_metric(self):
        run = self.runs["TGV", "ISPH"]
        record_run(run, summary={"errors": {"other": 0.5}, "wall_time_s": 1.0})
        self.assertEqual(classify_cell(run), ("ok", "no l1_velocity in summary.json", "other", 0.5, 1.0, None))

    def test_failed_during_time_stepping(self):
        run = self.runs["TGV", "WCSPH"]
        record_run(run, status="failed", failure="x", returncode=1,
                   summary={"status": "failed", "failure": "step 12 (t = 0.034): non-finite velocity at particle 7",
                            "errors": {}, "wall_time_s": 0.1, "steps": 12})
        c = classify_cell(run)
        self.assertEqual(c[0], "failed")
        self.assertEqual(cell_text(c), "**failed**: non-finite velocity at particle 7")

    def test_timeout_and_signal_are_failures(self):
        run = self.runs["TGV", "WCSPH"]
        record_run(run, status="failed", failure="timed out after 5 s (--timeout)", returncode=None)
        self.assertEqual(classify_cell(run)[0], "failed")
        record_run(run, status="failed", failure="killed by signal 9", returncode=-9)
        self.assertEqual(classify_cell(run)[0], "failed")

    def test_refused_at_start_up(self):
        run = self.runs["Sod", "ISPH"]
        record_run(run, status="failed", failure=GAS, returncode=1, elapsed_s=0.2)
        c = classify_cell(run)
        self.assertEqual(c, ("n/a", GAS, "l1_density", None, 0.2, None))
        self.assertEqual(cell_text(c), "n/a (%s)" % short_reason(GAS, 80))

    def test_option_error(self):
        run = self.runs["Sod", "WCSPH"]
        record_run(run, status="failed", failure="-density_diffusion: unknown value none", returncode=1)
        c = classify_cell(run)
        self.assertEqual(c[0], "error")
        self.assertEqual(cell_text(c), "**error**: -density_diffusion: unknown value none")

    def test_matrix_csv_and_md(self):
        record_run(self.runs["TGV", "ISPH"], summary={"errors": {"l1_velocity": 0.02}, "wall_time_s": 1.5, "steps": 4})
        record_run(self.runs["TGV", "WCSPH"], summary={"errors": {"l1_velocity": 0.01}, "wall_time_s": 0.5, "steps": 9})
        record_run(self.runs["TGV", "gas"], status="failed", failure="needs a gas scene", returncode=1)
        record_run(self.runs["Sod", "ISPH"], status="failed", failure=GAS, returncode=1)
        record_run(self.runs["Sod", "WCSPH"], status="failed", failure="step 2 (t = 0.1): boom",
                   summary={"status": "failed", "failure": "step 2 (t = 0.1): boom"})
        # Sod x gas: not run
        runs = list(self.runs.values())
        make_matrix_outputs(self.study, os.path.join(self.tmp, "mini.yaml"), runs, self.out, (5, 0, 3))
        with open(os.path.join(self.out, "matrix.csv")) as f:
            rows = list(csv.reader(f))
        self.assertEqual(rows[0], ["row", "column", "status", "reason", "metric", "value", "wall_time_s", "steps",
                                   "energy_created", "energy_scale", "run_dir"])
        self.assertEqual(rows[1], ["TGV", "ISPH", "ok", "", "l1_velocity", "0.02", "1.5", "4", "", "", "r1-TGV--c1-ISPH"])
        self.assertEqual(rows[4][:4], ["Sod", "ISPH", "n/a", GAS])
        self.assertEqual(rows[5][:4], ["Sod", "WCSPH", "failed", "boom"])
        self.assertEqual(rows[6], ["Sod", "gas", "not run", "", "l1_density", "", "", "", "", "", "r2-Sod--c3-gas"])
        with open(os.path.join(self.out, "matrix.md")) as f:
            md = f.read()
        self.assertTrue(md.startswith("# Stability matrix: mini\n\nA 2 x 3 matrix.\n\nStudy file `%s`; 6 cells (5 run now, "
                                      "0 up to date)." % os.path.join(self.tmp, "mini.yaml")))
        self.assertIn("Columns: **ISPH** = `-solver isph`; **WCSPH** = `-solver wcsph -density_diffusion none`; "
                      "**gas** = `-solver compressible`\n", md)
        self.assertIn("| case | ISPH | WCSPH | gas |\n|---|---|---|---|\n"
                      "| TGV | ok, l1_velocity=0.02 (1.5 s) | ok, l1_velocity=0.01 (0.5 s†) | n/a (needs a gas scene) |\n"
                      "| Sod | n/a (%s) | **failed**: boom | not run |\n\n"
                      "† wall time < 1 s: timer noise, not a measure of speed.\n" % short_reason(GAS, 80), md)
        self.assertIn("- **TGV** (`-case taylor_green -nx 8`): survived with ISPH, WCSPH (lowest `l1_velocity`: WCSPH, "
                      "0.01); not applicable: gas.\n"
                      "- **Sod** (`-case sod -nx 48`): no variant survived; failed: WCSPH; not applicable: ISPH; "
                      "not run: gas.\n", md)
        self.assertIn("Full reasons:\n\n- TGV × gas: needs a gas scene (`r1-TGV--c3-gas`)\n", md)


SCENE_MATRIX = """\
name: scenes
matrix:
  rows:
    - {label: still, scene: [still_water, --nx, 8]}
    - {label: bad, scene: [no_such_scene]}
  columns:
    - {label: ISPH, solver: isph}
    - {label: WCSPH, solver: wcsph}
"""


class SceneRows(TempDirCase):
    """Rows made by scripts/make-scene: run as -case scene on a file named by the scene's arguments."""

    def setUp(self):
        super().setUp()
        study = load_study(self.write("scenes.yaml", SCENE_MATRIX))
        self.out = os.path.join(self.tmp, "m")
        self.runs = {(r["row"], r["column"]): r for r in plan_matrix_runs(study, self.out, "/opt/sph", 0)}

    def test_planned_as_scene_runs_on_one_file(self):
        isph, wcsph = self.runs["still", "ISPH"], self.runs["still", "WCSPH"]
        scene = os.path.join(self.out, "scenes", "still_water_--nx_8.vtp")
        for run in (isph, wcsph):
            self.assertEqual(run["args"][:4], ["-case", "scene", "-solver", run["solver"]])
            self.assertEqual(run["args"][run["args"].index("-scene_file") + 1], scene)
            self.assertNotIn("-nx", run["args"])
        self.assertIsNone(make_scene(isph["scene"]))
        first = os.path.getmtime(scene)
        self.assertIsNone(make_scene(wcsph["scene"]))  # made once for the row
        self.assertEqual(os.path.getmtime(scene), first)

    def test_a_scene_make_scene_refuses_is_a_failed_cell(self):
        msg = make_scene(self.runs["bad", "ISPH"]["scene"])
        self.assertTrue(msg.startswith("make-scene no_such_scene failed: "), msg)


if __name__ == "__main__":
    unittest.main()
