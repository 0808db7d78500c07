"""plan.py: loading and checking study files, the runs, their options, folders and command lines."""

import glob
import os
import unittest

from sph_study.plan import (load_study, option_args, option_value, plan_matrix_runs, plan_runs, resolution_options,
                            safe_name, sweep_choice)
from sph_study.tests.support import STUDIES, TempDirCase, study_file

SPH = "/opt/sph"


def options_of(run):
    """The run's sph arguments as {option: value} (None for a flag)."""
    out, args, i = {}, run["args"], 0
    while i < len(args):
        if i + 1 < len(args) and not (args[i + 1].startswith("-") and not args[i + 1][1:2].isdigit()):
            out[args[i][1:]] = args[i + 1]
            i += 2
        else:
            out[args[i][1:]] = None
            i += 1
    return out


class Options(unittest.TestCase):
    def test_option_values(self):
        self.assertEqual(option_value(True), "1")
        self.assertEqual(option_value(False), "0")
        self.assertEqual(option_value(0.1), "0.1")
        self.assertEqual(option_value(1e-3), "0.001")
        self.assertEqual(option_value(100), "100")
        self.assertIsNone(option_value(None))

    def test_booleans_as_1_0_flags_without_value(self):
        self.assertEqual(option_args({"shifting": False, "-ppe_ksp_monitor": None, "re": 100}),
                         ["-shifting", "0", "-ppe_ksp_monitor", "-re", "100"])
        self.assertEqual(option_args({"label": ""}), ["-label"])

    def test_sweep_with_a_mapping_value(self):
        self.assertEqual(sweep_choice("ksp", {"ppe_ksp_type": "gmres", "ppe_pc_type": "jacobi"}),
                         ("gmres+jacobi", {"ppe_ksp_type": "gmres", "ppe_pc_type": "jacobi"}))
        self.assertEqual(sweep_choice("ksp", {"label": "cg/hypre", "ppe_ksp_type": "cg", "ppe_pc_type": "hypre"}),
                         ("cg/hypre", {"ppe_ksp_type": "cg", "ppe_pc_type": "hypre"}))

    def test_sweep_with_a_scalar_value(self):
        self.assertEqual(sweep_choice("shifting", False), ("0", {"shifting": False}))
        self.assertEqual(sweep_choice("cfl", 0.25), ("0.25", {"cfl": 0.25}))
        self.assertEqual(sweep_choice("ppe_ksp_monitor", None), ("", {"ppe_ksp_monitor": None}))

    def test_safe_name(self):
        self.assertEqual(safe_name("isph-ksp=cg+hypre-nx32"), "isph-ksp=cg+hypre-nx32")
        self.assertEqual(safe_name("r1-TGV Re 1000, t 5--c4-WCSPH no δ-SPH"), "r1-TGV_Re_1000__t_5--c4-WCSPH_no__-SPH")


class LoadStudy(TempDirCase):
    def test_tiny_test(self):
        s = load_study(study_file("tiny_test.yaml"))
        self.assertEqual(s["name"], "tiny_test")
        self.assertEqual(s["case"], "taylor_green")
        self.assertEqual(s["solvers"], ["isph", "wcsph"])
        self.assertEqual(s["resolutions"], [8, 12])
        self.assertEqual(s["options"], {"re": 100, "t_end": 0.05})
        self.assertEqual(s["solver_sweeps"], {"isph": {"cfl": [0.2, 5]}})
        self.assertEqual(s["metric"], "l1_velocity")
        for key in ("sweeps", "solver_options", "resolution_options", "solver_resolution_options"):
            self.assertEqual(s[key], {})
        self.assertNotIn("levels", s)

    def test_every_study_file_of_the_repository_loads_and_plans(self):
        files = sorted(glob.glob(os.path.join(STUDIES, "*.yaml")))
        self.assertIn(study_file("tiny_test.yaml"), files)
        for path in files:
            with self.subTest(study=os.path.basename(path)):
                s = load_study(path)
                if "matrix" in s:
                    runs = plan_matrix_runs(s, self.tmp, SPH, 0)
                    self.assertEqual(len(runs), len(s["matrix"]["rows"]) * len(s["matrix"]["columns"]))
                else:
                    runs = plan_runs(s, self.tmp, SPH, 0)
                    self.assertGreaterEqual(len(runs), len(s["resolutions"]) * len(s["solvers"]))
                    self.assertEqual(s["resolutions"], sorted(s["resolutions"]))
                self.assertEqual(len({r["dir"] for r in runs}), len(runs), "two runs share a folder")

    def test_defaults(self):
        path = self.write("my_study.yaml", "case: poiseuille\nsolver: wcsph\nresolutions: [16]\n")
        s = load_study(path)
        self.assertEqual((s["name"], s["solvers"], s["metric"]), ("my_study", ["wcsph"], "l1_velocity"))

    def test_json_study_file(self):
        path = self.write("j.json", '{"case": "taylor_green", "solvers": ["isph"], "resolutions": [16, 8], "mpi": 2}')
        s = load_study(path)
        self.assertEqual((s["name"], s["resolutions"], s["mpi"]), ("j", [8, 16], 2))

    def test_levels_are_numbers_sorted_down(self):
        # YAML 1.1 reads 1e-3 (no dot) as a string: still a level.
        path = self.write("l.yaml", "case: c\nsolvers: [wcsph]\nresolutions: [8]\nlevels: [1e-3, 0.5, 3.0e-4]\n")
        self.assertEqual(load_study(path)["levels"], [0.5, 1e-3, 3e-4])

    def refused(self, text, name="s.yaml"):
        path = self.write(name, text)
        with self.assertRaises(SystemExit) as cm:
            load_study(path)
        return str(cm.exception.code), path

    def test_refusals(self):
        msg, path = self.refused("case: c\nsolvers: [wcsph]\nresolutions: [8]\nbogus: 1\n")
        self.assertEqual(msg, "study: %s: unknown key(s) bogus (known: case, description, levels, metric, mpi, "
                              "name, options, resolution_options, resolutions, scene, solver, solver_options, "
                              "solver_resolution_options, solver_sweeps, solvers, sweeps)" % path)
        msg, path = self.refused("solvers: [wcsph]\nresolutions: [8]\n")
        self.assertEqual(msg, "study: %s: missing 'case'" % path)
        msg, path = self.refused("case: c\nresolutions: [8]\n")
        self.assertEqual(msg, "study: %s: missing 'solvers'" % path)
        msg, path = self.refused("case: c\nsolvers: [wcsph]\nresolutions: [8]\nsweeps: {cfl: []}\n")
        self.assertEqual(msg, "study: %s: sweep 'cfl' must be a non-empty list" % path)
        msg, path = self.refused("case: c\nsolvers: [wcsph]\nresolutions: [8]\noptions: [1]\n")
        self.assertEqual(msg, "study: %s: 'options' must be a mapping" % path)
        msg, path = self.refused("case: c\nsolvers: [wcsph]\nresolutions: [8]\nlevels: [1e-3, -1]\n")
        self.assertEqual(msg, "study: %s: 'levels' must be a list of positive error levels, e.g. [1e-3, 3e-4]" % path)
        for name in ("../../victim", "/tmp/victim", "..", "a/b", "[1]"):
            msg, path = self.refused("name: %s\ncase: c\nsolvers: [wcsph]\nresolutions: [8]\n" % name)
            self.assertIn("'name' must be a plain folder name (no '/', not '.' or '..')", msg)
            msg, path = self.refused("name: %s\nmatrix: {rows: [{case: c}], columns: [{solver: isph}]}\n" % name)
            self.assertIn("'name' must be a plain folder name", msg)
        msg, path = self.refused("[1, 2]\n")
        self.assertEqual(msg, "study: %s: expected a mapping at the top level" % path)

    def test_wrong_types(self):
        """A key of the wrong type is one line naming it, not a Python traceback."""
        base = "case: c\nsolvers: [wcsph]\nresolutions: [8]\n"
        for text, expected in (
                ("case: c\nsolvers: [wcsph]\nresolutions: 8\n", "'resolutions' must be a list of positive integers"),
                ("case: c\nsolvers: [wcsph]\nresolutions: [a, 8]\n", "'resolutions' must be a list of positive"),
                ("case: c\nsolvers: 5\nresolutions: [8]\n", "'solvers' must be a solver name or a list of them"),
                ("case: c\nsolvers: [[wcsph]]\nresolutions: [8]\n", "'solvers' must be a solver name"),
                ("case: [c]\nsolvers: [wcsph]\nresolutions: [8]\n", "'case' must be a case name"),
                (base + "mpi: two\n", "'mpi' must be a number of MPI ranks"),
                (base + "solver_options: {wcsph: 3}\n", "'solver_options: wcsph' must be a mapping of options"),
                (base + "options: {nx: [1, 2]}\n", "option 'nx' must be one value, got [1, 2]; a list of values is a sweep"),
                ("case: c\nsolvers: [wcsph\n", "line 3: not valid YAML"),
                ("matrix: {rows: [{case: c}], columns: [{solver: isph}], options: [1]}\n",
                 "matrix: 'options' must be a mapping of options")):
            msg, path = self.refused(text)
            self.assertIn(expected, msg)
            self.assertTrue(msg.startswith("study: %s: " % path) and "\n" not in msg, msg)


class ResolutionOptions(TempDirCase):
    REFINED = ("name: tiny_refined\ncase: taylor_green\nsolvers: [wcsph, isph]\nresolutions: [12, 8]\n"
               "options: {re: 100, t_end: 0.02}\n"
               "resolution_options: {delta: [0.05, 0.1]}\n"
               "solver_resolution_options:\n  wcsph: {c0_factor: [20, 10], delta: [0.025, 0.2]}\n")

    def test_values_follow_their_resolution(self):
        s = load_study(self.write("r.yaml", self.REFINED))
        self.assertEqual(s["resolutions"], [8, 12])  # increasing nx, the values follow
        self.assertEqual(s["resolution_options"], {"delta": [0.1, 0.05]})
        self.assertEqual(s["solver_resolution_options"], {"wcsph": {"c0_factor": [10, 20], "delta": [0.2, 0.025]}})
        # every solver's, then the solver's own (which wins)
        self.assertEqual(resolution_options(s, "wcsph", 0), {"delta": 0.2, "c0_factor": 10})
        self.assertEqual(resolution_options(s, "wcsph", 1), {"delta": 0.025, "c0_factor": 20})
        self.assertEqual(resolution_options(s, "isph", 1), {"delta": 0.05})

    def test_planned_runs_carry_their_resolution_s_values(self):
        s = load_study(self.write("r.yaml", self.REFINED))
        runs = {(r["solver"], r["nx"]): options_of(r) for r in plan_runs(s, self.tmp, SPH, 0)}
        self.assertEqual((runs["wcsph", 8]["c0_factor"], runs["wcsph", 8]["delta"]), ("10", "0.2"))
        self.assertEqual((runs["wcsph", 12]["c0_factor"], runs["wcsph", 12]["delta"]), ("20", "0.025"))
        self.assertEqual(runs["isph", 8]["delta"], "0.1")
        self.assertNotIn("c0_factor", runs["isph", 12])

    def test_one_value_per_resolution_is_needed(self):
        path = self.write("few.yaml", "case: taylor_green\nsolvers: wcsph\nresolutions: [12, 8]\n"
                                      "resolution_options: {c0_factor: [10]}\n")
        with self.assertRaises(SystemExit) as cm:
            load_study(path)
        self.assertEqual(str(cm.exception.code),
                         "study: %s: resolution_options 'c0_factor' needs one value per resolution (2), got [10]" % path)

    def test_one_value_per_resolution_is_needed_per_solver(self):
        path = self.write("few.yaml", self.REFINED.replace("c0_factor: [20, 10]", "c0_factor: [20]"))
        with self.assertRaises(SystemExit) as cm:
            load_study(path)
        self.assertEqual(str(cm.exception.code),
                         "study: %s: solver_resolution_options: wcsph 'c0_factor' needs one value per resolution (2), "
                         "got [20]" % path)

    def test_too_many_values_and_a_scalar_are_refused(self):
        for table in ("{c0_factor: [10, 20, 40]}", "{c0_factor: 10}"):
            path = self.write("bad.yaml", "case: c\nsolvers: wcsph\nresolutions: [12, 8]\nresolution_options: %s\n" % table)
            with self.subTest(table=table), self.assertRaises(SystemExit) as cm:
                load_study(path)
            self.assertIn("needs one value per resolution (2)", str(cm.exception.code))


class PlanRuns(TempDirCase):
    def test_tiny_test(self):
        s = load_study(study_file("tiny_test.yaml"))
        runs = plan_runs(s, self.tmp, SPH, 0)
        self.assertEqual([r["name"] for r in runs],
                         ["isph-cfl=0.2-nx8", "isph-cfl=0.2-nx12", "isph-cfl=5-nx8", "isph-cfl=5-nx12",
                          "wcsph-nx8", "wcsph-nx12"])
        self.assertEqual([r["label"] for r in runs], ["isph, cfl=0.2"] * 2 + ["isph, cfl=5"] * 2 + ["wcsph"] * 2)
        first = runs[0]
        self.assertEqual(first["args"], ["-case", "taylor_green", "-solver", "isph", "-nx", "8", "-re", "100",
                                         "-t_end", "0.05", "-cfl", "0.2", "-output_interval", "0", "-progress", "0",
                                         "-output_dir", os.path.join(self.tmp, "isph-cfl=0.2-nx8")])
        self.assertEqual(first["command"], [SPH] + first["args"])
        self.assertEqual((first["dir"], first["sweep"], first["mpi"], first["nx"], first["solver"]),
                         (os.path.join(self.tmp, "isph-cfl=0.2-nx8"), {"cfl": "0.2"}, 0, 8, "isph"))
        self.assertEqual(runs[-1]["sweep"], {})  # the ISPH sweep is ISPH's only

    def test_mpi_command(self):
        s = load_study(study_file("tiny_test.yaml"))
        run = plan_runs(s, self.tmp, SPH, 2)[0]
        self.assertEqual(run["command"][:6], ["mpirun", "-n", "2", "--allow-run-as-root", "--oversubscribe", SPH])
        self.assertEqual(run["mpi"], 2)
        self.assertEqual(plan_runs(s, self.tmp, SPH, None)[0]["mpi"], 0)

    def test_sweep_combinations(self):
        path = self.write("sw.yaml", """
case: taylor_green
solvers: [isph, wcsph]
resolutions: [16, 8]
options: {re: 100, output_interval: 5}
sweeps: {shifting: [1, 0]}
solver_options: {wcsph: {c0_factor: 10}}
solver_sweeps:
  isph:
    ksp: [{ppe_ksp_type: cg, ppe_pc_type: hypre}, {label: gm, ppe_ksp_type: gmres, ppe_pc_type: jacobi}, {ppe_ksp_type: bcgs}]
  wcsph:
    shifting: [0]
""")
        s = load_study(path)
        runs = plan_runs(s, self.tmp, SPH, 0)
        isph = [r for r in runs if r["solver"] == "isph"]
        wcsph = [r for r in runs if r["solver"] == "wcsph"]
        self.assertEqual(len(isph), 2 * 3 * 2)  # shifting x ksp x resolutions
        self.assertEqual(len(wcsph), 1 * 2)     # its own shifting sweep replaces the common one
        self.assertEqual(sorted({(r["sweep"]["shifting"], r["sweep"]["ksp"]) for r in isph}),
                         sorted((sh, k) for sh in ("1", "0") for k in ("cg+hypre", "gm", "bcgs")))
        self.assertEqual([r["name"] for r in isph[:2]], ["isph-shifting=1-ksp=cg+hypre-nx8",
                                                         "isph-shifting=1-ksp=cg+hypre-nx16"])
        self.assertEqual(isph[0]["label"], "isph, shifting=1, ksp=cg+hypre")
        gm = options_of([r for r in isph if r["sweep"]["ksp"] == "gm"][0])
        self.assertEqual((gm["ppe_ksp_type"], gm["ppe_pc_type"]), ("gmres", "jacobi"))
        self.assertNotIn("label", gm)
        self.assertEqual(gm["output_interval"], "5")  # the study's own, not the default 0
        w = options_of(wcsph[0])
        self.assertEqual((w["c0_factor"], w["shifting"]), ("10", "0"))
        self.assertNotIn("c0_factor", options_of(isph[0]))
        self.assertEqual(wcsph[0]["name"], "wcsph-shifting=0-nx8")


class SceneStudy(TempDirCase):
    """A scene at several resolutions: one file per resolution, made by scripts/make-scene or the study's
    own command (run in the study file's folder), and -case scene without -nx."""

    def plan(self, text):
        path = self.write("studies/scene.yaml", text)
        return path, plan_runs(load_study(path), os.path.join(self.tmp, "out"), SPH, 0)

    def test_make_scene_arguments_per_resolution(self):
        _, runs = self.plan("scene: [falling_block, --obstacle-shape, wedge]\nsolvers: [isph]\nresolutions: [40, 20]\n")
        self.assertEqual([r["nx"] for r in runs], [20, 40])
        for r in runs:
            o = options_of(r)
            self.assertEqual(o["case"], "scene")
            self.assertNotIn("nx", o)
            self.assertEqual(o["scene_file"], r["scene"]["file"])
            self.assertEqual(r["scene"]["args"], ["falling_block", "--obstacle-shape", "wedge", "--nx", str(r["nx"])])
        self.assertNotEqual(runs[0]["scene"]["file"], runs[1]["scene"]["file"])

    def test_own_command_runs_in_the_study_file_s_folder(self):
        path, runs = self.plan('scene: {command: [./make.py, --nx, "{nx}", -o, "{file}"]}\nsolvers: [wcsph]\n'
                               'resolutions: [16]\n')
        scene = runs[0]["scene"]
        self.assertEqual(scene["command"], ["./make.py", "--nx", "16", "-o", scene["file"]])
        self.assertEqual(scene["cwd"], os.path.dirname(path))
        self.assertTrue(scene["file"].startswith(os.path.join(self.tmp, "out", "scenes")))

    def test_relative_scene_file_is_the_study_file_s(self):
        path, runs = self.plan("case: scene\nsolvers: [isph]\nresolutions: [8]\noptions: {scene_file: block.vtp}\n")
        self.assertEqual(options_of(runs[0])["scene_file"], os.path.join(os.path.dirname(path), "block.vtp"))

    def test_refusals(self):
        for text in ("case: taylor_green\nscene: [cavity]\nsolvers: [isph]\nresolutions: [8]\n",
                     "scene: []\nsolvers: [isph]\nresolutions: [8]\n",
                     "scene: {command: [./make.py, --nx, '{nx}']}\nsolvers: [isph]\nresolutions: [8]\n"):
            path = self.write("bad.yaml", text)
            with self.assertRaises(SystemExit) as e:
                load_study(path)
            self.assertIn("scene", str(e.exception))


class MatrixPlan(TempDirCase):
    def test_stability_matrix(self):
        s = load_study(study_file("stability.yaml"))
        m = s["matrix"]
        self.assertEqual(s["name"], "stability")
        runs = plan_matrix_runs(s, self.tmp, SPH, 0)
        self.assertEqual(len(runs), len(m["rows"]) * len(m["columns"]))
        cols = [c["label"] for c in m["columns"]]
        first = runs[0]
        self.assertEqual((first["row"], first["column"], first["label"]),
                         (m["rows"][0]["label"], cols[0], "%s | %s" % (m["rows"][0]["label"], cols[0])))
        self.assertEqual(first["name"], "r1-%s--c1-%s" % (m["rows"][0]["label"], cols[0]))
        self.assertEqual(os.path.basename(first["dir"]), safe_name(first["name"]))
        self.assertEqual(first["nx"], int(m["rows"][0]["options"]["nx"]))
        self.assertEqual(first["metric"], m["rows"][0]["metric"])
        o = options_of(first)
        self.assertEqual((o["output_interval"], o["checkpoint_interval"], o["progress"]), ("0", "0", "0"))
        # a row's solver_options reach only the columns of that solver
        for r in runs:
            o = options_of(r)
            if r["row"] == "Sod 1D":
                self.assertEqual("kernel" in o, r["solver"] == "compressible", r["name"])
            if r["row"] == "TGV Re 100, ISPH at CFL 1":
                self.assertEqual(o.get("cfl"), "1.0" if r["solver"] == "isph" else None, r["name"])

    def test_matrix_options_and_label_keyed_solver_options(self):
        path = self.write("m.yaml", """
matrix:
  options: {t_end: 0.1}
  metric: l1_velocity
  rows:
    - {case: taylor_green, options: {nx: 8}, solver_options: {B: {re: 50}}}
  columns:
    - {label: A, solver: wcsph, options: {t_end: 0.2}}
    - {label: B, solver: wcsph}
""")
        s = load_study(path)
        self.assertEqual(s["name"], "m")
        self.assertEqual(s["matrix"]["rows"][0]["label"], "taylor_green")
        self.assertEqual(s["matrix"]["rows"][0]["metric"], "l1_velocity")
        a, b = plan_matrix_runs(s, self.tmp, SPH, 3)
        self.assertEqual(options_of(a)["t_end"], "0.2")
        self.assertNotIn("re", options_of(a))
        self.assertEqual((options_of(b)["t_end"], options_of(b)["re"]), ("0.1", "50"))
        self.assertEqual(a["command"][:3], ["mpirun", "-n", "3"])
        self.assertEqual(a["sweep"], {})

    def test_matrix_refusals(self):
        cases = [
            ("matrix: {rows: [{case: a}], columns: [{solver: b}, {solver: b}]}\n",
             "matrix: two columns labelled 'b'"),
            ("matrix: {rows: [{case: a, x: 1}], columns: [{solver: b}]}\n",
             "matrix: rows[0]: unknown key(s) x (known: case, label, metric, options, scene, solver_options)"),
            ("matrix: {rows: [{case: a}], columns: [{solver: b}]}\nfoo: 1\n",
             "with 'matrix:', unknown key(s) foo (known: description, matrix, mpi, name)"),
            ("matrix: {rows: [], columns: [{solver: b}]}\n", "matrix: 'rows' must be a non-empty list"),
            ("matrix: {rows: [{label: x}], columns: [{solver: b}]}\n", "matrix: rows[0] must be a mapping with 'case'"),
            ("matrix: [1]\n", "'matrix' must be a mapping with 'rows' and 'columns'"),
        ]
        for text, want in cases:
            path = self.write("bad.yaml", text)
            with self.subTest(want=want), self.assertRaises(SystemExit) as cm:
                load_study(path)
            self.assertEqual(str(cm.exception.code), "study: %s: %s" % (path, want))


if __name__ == "__main__":
    unittest.main()
