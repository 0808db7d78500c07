"""cli.py and the scripts/study entry point: --nx, --dry-run, the matrix form, -h, --self-test (no runs of
the sph program: --dry-run only prints the commands)."""

import contextlib
import io
import os
import subprocess
import sys
import unittest

from sph_study import cli
from sph_study.common import REPO
from sph_study.plan import load_study, plan_runs
from sph_study.tests.support import TempDirCase, record_run, study_file

ENTRY = os.path.join(REPO, "scripts", "study")
REFINED = """\
name: tiny_refined
case: taylor_green
solvers: [wcsph]
resolutions: [12, 8]
options: {re: 100, t_end: 0.02}
solver_resolution_options:
  wcsph: {c0_factor: [20, 10]}
levels: [0.5, 1e-9]
"""


def main(*argv):
    """(exit code, stdout, stderr) of cli.main(argv); argparse's and sys.exit's exits included."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            rc = cli.main(list(argv))
        except SystemExit as e:
            rc = e.code
            if isinstance(rc, str):
                err.write(rc + "\n")
    return rc, out.getvalue(), err.getvalue()


class DryRun(TempDirCase):
    def test_plans_every_run(self):
        rc, out, _ = main(study_file("tiny_test.yaml"), "--sph", "/opt/sph", "--out", self.tmp, "--dry-run")
        self.assertEqual(rc, 0)
        lines = out.splitlines()
        self.assertEqual(len(lines), 6)
        self.assertEqual(lines[0], "run  /opt/sph -case taylor_green -solver isph -nx 8 -re 100 -t_end 0.05 -cfl 0.2 "
                                   "-output_interval 0 -progress 0 -output_dir %s/isph-cfl=0.2-nx8" % self.tmp)
        self.assertFalse(os.listdir(self.tmp))  # nothing written

    def test_up_to_date_runs_are_skipped(self):
        study = load_study(study_file("tiny_test.yaml"))
        runs = plan_runs(study, self.tmp, os.path.abspath("/opt/sph"), 2)
        record_run(runs[0], summary={"status": "completed"})
        rc, out, _ = main(study_file("tiny_test.yaml"), "--sph", "/opt/sph", "--out", self.tmp, "--mpi", "2",
                          "--dry-run")
        lines = out.splitlines()
        self.assertTrue(lines[0].startswith("skip mpirun -n 2 --allow-run-as-root --oversubscribe /opt/sph "), lines[0])
        self.assertTrue(all(l.startswith("run  ") for l in lines[1:]))

    def test_study_mpi_is_the_default(self):
        path = self.write("j.json", '{"case": "c", "solvers": ["isph"], "resolutions": [8], "mpi": 3}')
        rc, out, _ = main(path, "--out", self.tmp, "--dry-run")
        self.assertTrue(out.startswith("run  mpirun -n 3 "), out)
        rc, out, _ = main(path, "--out", self.tmp, "--dry-run", "--mpi", "0")
        self.assertTrue(out.startswith("run  %s " % os.path.join(REPO, "build", "sph")), out)

    def test_nx_not_in_the_study_file_is_planned(self):
        rc, out, _ = main(study_file("tiny_test.yaml"), "--out", self.tmp, "--nx", "9", "--dry-run")
        self.assertEqual(rc, 0)
        lines = out.splitlines()
        self.assertEqual(len(lines), 3)
        self.assertTrue(all(" -nx 9 " in l for l in lines), lines)

    def test_nx_replaces_the_study_s_resolutions(self):
        rc, out, _ = main(study_file("tiny_test.yaml"), "--out", self.tmp, "--nx", "16", "8", "16", "--dry-run")
        nxs = [l.split(" -nx ")[1].split()[0] for l in out.splitlines()]
        self.assertEqual(nxs, ["8", "16"] * 3)

    def test_nx_keeps_the_resolution_options_of_its_resolution(self):
        path = self.write("refined.yaml", REFINED)
        rc, out, _ = main(path, "--out", self.tmp, "--nx", "12", "--dry-run")
        self.assertEqual(rc, 0)
        self.assertEqual(len(out.splitlines()), 1)
        self.assertIn(" -nx 12 ", out)
        self.assertIn(" -c0_factor 20 ", out)
        self.assertNotIn(" -nx 8 ", out)

    def test_nx_outside_the_resolution_options_is_refused(self):
        path = self.write("refined.yaml", REFINED)
        rc, out, err = main(path, "--out", self.tmp, "--nx", "9", "12", "--dry-run")
        self.assertEqual(rc, 2)
        self.assertEqual(out, "")
        self.assertIn("error: --nx [9]: not among the study's resolutions [8, 12], which its resolution options follow",
                      err)

    def test_nx_does_not_apply_to_a_matrix(self):
        rc, out, err = main(study_file("stability.yaml"), "--out", self.tmp, "--nx", "16", "--dry-run")
        self.assertEqual(rc, "study: --nx does not apply to a matrix study (set nx in the rows' options)")

    def test_matrix_dry_run(self):
        study = load_study(study_file("stability.yaml"))
        rc, out, _ = main(study_file("stability.yaml"), "--sph", "/opt/sph", "--out", self.tmp, "--dry-run")
        self.assertEqual(rc, 0)
        lines = out.splitlines()
        self.assertEqual(len(lines), len(study["matrix"]["rows"]) * len(study["matrix"]["columns"]))
        self.assertTrue(lines[0].startswith("run  /opt/sph -case taylor_green -solver isph -nx 32 "), lines[0])

    def test_refusals(self):
        rc, _, err = main()
        self.assertEqual(rc, 2)
        self.assertIn("error: a study file is needed (or --self-test)", err)
        rc, _, err = main(os.path.join(self.tmp, "none.yaml"))
        self.assertEqual(rc, 2)
        self.assertIn("error: no study file %s" % os.path.join(self.tmp, "none.yaml"), err)
        rc, _, err = main(study_file("tiny_test.yaml"), "--sph", os.path.join(self.tmp, "no_sph"), "--out", self.tmp)
        self.assertEqual(rc, "study: no sph executable at %s (build it with scripts/build, or pass --sph PATH)"
                         % os.path.join(self.tmp, "no_sph"))

    def test_every_run_failed_is_an_error(self):
        fake = os.path.join(self.tmp, "sph")
        with open(fake, "w") as f:
            f.write("#!/bin/sh\necho 'sph: error: refused' >&2\nexit 1\n")
        os.chmod(fake, 0o755)
        rc, _, err = main(study_file("tiny_test.yaml"), "--sph", fake, "--out", os.path.join(self.tmp, "s"))
        self.assertEqual(rc, 1)
        self.assertIn("study: every run failed", err)

    def test_self_test(self):
        rc, out, _ = main("--self-test")
        self.assertEqual(rc, 0)
        self.assertTrue(out.endswith("checks passed\n"))


class EntryPoint(unittest.TestCase):
    """scripts/study itself, as the user and tests/cli/study.sh run it."""

    def run_entry(self, *args):
        return subprocess.run([sys.executable, ENTRY] + list(args), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True, cwd=REPO)

    def test_executable_with_the_system_python(self):
        self.assertTrue(os.access(ENTRY, os.X_OK))
        with open(ENTRY) as f:
            self.assertEqual(f.readline(), "#!/usr/bin/python3\n")

    def test_help_is_the_usage_text(self):
        p = self.run_entry("-h")
        self.assertEqual(p.returncode, 0)
        doc = cli.__doc__.split("\n\n")
        self.assertTrue(p.stdout.startswith("usage: study [-h] [-j JOBS] [--mpi MPI]"), p.stdout)
        self.assertIn("\n\n%s\n\n" % doc[0], p.stdout)  # description: the first paragraph
        self.assertIn("\n\n".join(doc[2:]).rstrip("\n"), p.stdout)  # epilog: the study file keys and on
        self.assertIn("Study file keys:", p.stdout)
        self.assertIn("--self-test", p.stdout)

    def test_self_test(self):
        p = self.run_entry("--self-test")
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("ok   order 4e-2 -> 1e-2 at h 0.1 -> 0.05 is 2\n", p.stdout)
        self.assertTrue(p.stdout.endswith("self-test: 26 of 26 checks passed\n"))


if __name__ == "__main__":
    unittest.main()
