"""execute.py: failure reasons, up-to-date checks, and run_all / execute with a stand-in program (a small
Python script, not the sph program)."""

import contextlib
import io
import os
import stat
import sys
import textwrap
import unittest

from sph_study.common import read_json, write_json
from sph_study.execute import failure_message, run_all, up_to_date
from sph_study.plan import load_study, plan_runs
from sph_study.tests.support import TempDirCase, record_run, study_file

# Stands in for the sph program: refuses -cfl 5 like the program does, else writes a summary.json.
FAKE_SPH = textwrap.dedent("""\
    #!%s
    import json, os, sys
    args = sys.argv[1:]
    out = args[args.index("-output_dir") + 1]
    if "-cfl" in args and args[args.index("-cfl") + 1] == "5":
        sys.stderr.write("some noise\\nsph: error: -cfl must be in (0, 1] (got 5)\\n")
        sys.exit(1)
    nx = int(args[args.index("-nx") + 1])
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump({"status": "completed", "n_particles": nx * nx, "kernel": {"h": 1.5 / nx}, "steps": 3,
                   "wall_time_s": 0.01, "errors": {"l1_velocity": 1.0 / nx ** 2, "linf_velocity": 1.0 / nx}}, f)
    print("done")
    """) % sys.executable


class FailureMessage(unittest.TestCase):
    def test_the_sph_error_line(self):
        self.assertEqual(failure_message("noise\nsph: error: -cfl must be in (0, 1] (got 5)\n", 1),
                         "-cfl must be in (0, 1] (got 5)")

    def test_the_last_sph_error_line_wins(self):
        self.assertEqual(failure_message("sph: error: first\n[1] sph: error: second  \nmore\n", 1), "second")

    def test_a_petsc_signal(self):
        msg = failure_message("[0]PETSC ERROR: Caught signal number 11 SEGV: Segmentation Violation\nx\n", 59)
        self.assertEqual(msg, "Caught signal number 11 SEGV: Segmentation Violation")

    def test_killed_by_a_signal(self):
        self.assertEqual(failure_message("", -9), "killed by signal 9")

    def test_last_line_otherwise(self):
        self.assertEqual(failure_message("a\nboom\n", 3), "exit code 3: boom")
        self.assertEqual(failure_message("", 3), "exit code 3")
        self.assertEqual(failure_message(None, 2), "exit code 2")


class UpToDate(TempDirCase):
    def run_of(self, mpi=0):
        return plan_runs(load_study(study_file("tiny_test.yaml")), self.tmp, "/opt/sph", mpi)[0]

    def test_no_record(self):
        self.assertFalse(up_to_date(self.run_of()))

    def test_summary_of_the_same_arguments(self):
        run = self.run_of()
        record_run(run, summary={"status": "completed"})
        self.assertTrue(up_to_date(run))

    def test_recorded_failure(self):
        run = self.run_of()
        record_run(run, status="failed", failure="boom")
        self.assertTrue(up_to_date(run))

    def test_completed_record_without_summary(self):
        run = self.run_of()
        record_run(run, status="completed")
        self.assertFalse(up_to_date(run))

    def test_other_arguments_or_ranks(self):
        run = self.run_of()
        record_run(run, summary={"status": "completed"})
        other = dict(run, args=run["args"][:-2] + ["-output_dir", "elsewhere"])
        self.assertFalse(up_to_date(other))
        self.assertFalse(up_to_date(dict(run, mpi=2)))


class Json(TempDirCase):
    def test_write_and_read(self):
        path = os.path.join(self.tmp, "x.json")
        write_json(path, {"a": [1, 2]})
        self.assertEqual(read_json(path), {"a": [1, 2]})
        self.assertFalse(os.path.exists(path + ".tmp"))
        with open(path) as f:
            self.assertTrue(f.read().endswith("}\n"))

    def test_missing_or_broken(self):
        self.assertIsNone(read_json(os.path.join(self.tmp, "none.json")))
        self.assertIsNone(read_json(self.write("bad.json", "{")))


class RunAll(TempDirCase):
    def setUp(self):
        super().setUp()
        self.sph = self.write("fake_sph", FAKE_SPH)
        os.chmod(self.sph, os.stat(self.sph).st_mode | stat.S_IXUSR)
        self.out = os.path.join(self.tmp, "study")
        self.runs = plan_runs(load_study(study_file("tiny_test.yaml")), self.out, self.sph, 0)

    def run_all(self, **kw):
        args = dict(jobs=2, timeout=60, force=False, retry_failed=False, metric="l1_velocity")
        args.update(kw)
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            counts = run_all(self.runs, **args)
        return counts, out.getvalue().splitlines()

    def test_runs_failures_and_skips(self):
        counts, lines = self.run_all()
        self.assertEqual(counts, (6, 0, 2))
        self.assertEqual(lines[0], "running 6 runs (2 at a time)")
        self.assertEqual(lines[-1], "ran 6 runs (2 failed), skipped 0 runs (up to date)")
        self.assertIn("isph, cfl=5 nx=8: FAILED: -cfl must be in (0, 1] (got 5)", "\n".join(lines))
        self.assertIn("wcsph nx=8: ", "\n".join(lines))
        self.assertIn(", l1_velocity 0.0156", "\n".join(lines))

        failed = read_json(os.path.join(self.out, "isph-cfl=5-nx8", "run.json"))
        self.assertEqual((failed["status"], failed["failure"], failed["returncode"]),
                         ("failed", "-cfl must be in (0, 1] (got 5)", 1))
        self.assertEqual(failed["command"], self.runs[2]["command"] + ["-overwrite"])
        self.assertEqual(failed["args"], self.runs[2]["args"])
        with open(os.path.join(self.out, "isph-cfl=5-nx8", "stderr.txt")) as f:
            self.assertIn("sph: error:", f.read())
        ok = read_json(os.path.join(self.out, "wcsph-nx12", "run.json"))
        self.assertEqual((ok["status"], ok["returncode"], ok["mpi"], ok["jobs"]), ("completed", 0, 0, 2))
        with open(os.path.join(self.out, "wcsph-nx12", "stdout.txt")) as f:
            self.assertEqual(f.read(), "done\n")

        counts, lines = self.run_all()
        self.assertEqual((counts, lines), ((0, 6, 0), ["ran 0 runs (0 failed), skipped 6 runs (up to date)"]))
        counts, lines = self.run_all(retry_failed=True)
        self.assertEqual(counts, (2, 4, 2))
        self.assertEqual(lines[0], "running 2 runs (2 at a time), skipping 4 up to date")
        counts, _ = self.run_all(force=True)
        self.assertEqual(counts, (6, 0, 2))

    def test_a_missing_program_is_a_failure(self):
        self.runs = [dict(r, command=[os.path.join(self.tmp, "no_such_sph")] + r["args"]) for r in self.runs[:1]]
        counts, lines = self.run_all()
        self.assertEqual(counts, (1, 0, 1))
        rec = read_json(os.path.join(self.runs[0]["dir"], "run.json"))
        self.assertEqual(rec["returncode"], 127)
        self.assertTrue(rec["failure"].startswith("cannot run %s" % os.path.join(self.tmp, "no_such_sph")), rec)
        self.assertEqual(rec["status"], "failed")


if __name__ == "__main__":
    unittest.main()
