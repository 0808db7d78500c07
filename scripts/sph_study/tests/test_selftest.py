"""selftest.py: scripts/study --self-test prints the same 26 check lines as before the package split."""

import contextlib
import io
import unittest

from sph_study.selftest import self_test

CHECKS = """\
order 4e-2 -> 1e-2 at h 0.1 -> 0.05 is 2
order 1e-2 -> 5e-3 at h 0.1 -> 0.05 is 1
order of e ~ h^3 over a factor 3 in h is 3
order undefined for a zero error
order undefined for equal h
order undefined for missing values
negative order when the error grows
time to reach: A reaches 1e-2 at t = 10 (a run point)
time to reach: B reaches 1e-2 at t = sqrt(10) (interpolated)
time to reach: A reaches 2e-3 at t = 50
time to reach: unreachable level gives None
time to reach: level above the coarsest error is an upper bound
pareto: B ahead at 1e-2 by 10/sqrt(10)
pareto: only A reaches 5e-3 and 1e-3
pareto: automatic levels span 1e-1 .. 1e-3
nice levels between 3e-3 and 0.04
nice levels in a narrow range: 5 geometric 2-digit values
nice levels in a very narrow range
failure message: the sph: error line
failure message: a PETSc signal
failure message: last line otherwise
sweep with a mapping value
options: booleans as 1/0, flags without value
matrix: failure reason without the step prefix
matrix: long reasons are cut
matrix: option errors are not 'n/a'""".split("\n")


class SelfTest(unittest.TestCase):
    def test_every_check_passes_with_the_same_lines(self):
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            rc = self_test()
        self.assertEqual(rc, 0)
        self.assertEqual(out.getvalue().splitlines(),
                         ["ok   " + c for c in CHECKS] + ["self-test: %d of %d checks passed" % (len(CHECKS), len(CHECKS))])


if __name__ == "__main__":
    unittest.main()
