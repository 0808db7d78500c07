"""scripts/study --self-test: the order, Pareto, failure-message, option and matrix-reason checks, one
line each (the same checks are unit tests in tests/)."""

import math

from .execute import failure_message
from .matrix import option_problem, short_reason
from .orders import nice_levels, observed_order, pareto_table, time_to_reach
from .plan import option_args, sweep_choice


def self_test():
    checks = []

    def check(name, ok):
        checks.append((name, ok))
        print(("ok   " if ok else "FAIL ") + name)

    close = lambda a, b, tol=1e-12: a is not None and b is not None and abs(a - b) <= tol * max(1, abs(b))
    check("order 4e-2 -> 1e-2 at h 0.1 -> 0.05 is 2", close(observed_order(4e-2, 1e-2, 0.1, 0.05), 2.0))
    check("order 1e-2 -> 5e-3 at h 0.1 -> 0.05 is 1", close(observed_order(1e-2, 5e-3, 0.1, 0.05), 1.0))
    check("order of e ~ h^3 over a factor 3 in h is 3", close(observed_order(27e-3, 1e-3, 0.3, 0.1), 3.0))
    check("order undefined for a zero error", observed_order(0.0, 1e-2, 0.1, 0.05) is None)
    check("order undefined for equal h", observed_order(1e-2, 1e-3, 0.1, 0.1) is None)
    check("order undefined for missing values", observed_order(None, 1e-3, 0.1, 0.05) is None)
    check("negative order when the error grows", close(observed_order(1e-2, 2e-2, 0.1, 0.05), -1.0))
    # Two power-law lines: A has e = 0.1 / t, B has e = 0.1 / t^2; log-log interpolation is exact.
    A = [(1.0, 1e-1), (10.0, 1e-2), (100.0, 1e-3)]
    B = [(1.0, 1e-1), (2.0, 2.5e-2), (4.0, 6.25e-3)]
    tA, exA = time_to_reach(A, 1e-2)
    tB, exB = time_to_reach(B, 1e-2)
    check("time to reach: A reaches 1e-2 at t = 10 (a run point)", close(tA, 10.0) and exA)
    check("time to reach: B reaches 1e-2 at t = sqrt(10) (interpolated)", close(tB, math.sqrt(10.0)) and exB)
    check("time to reach: A reaches 2e-3 at t = 50", close(time_to_reach(A, 2e-3)[0], 50.0))
    check("time to reach: unreachable level gives None", time_to_reach(B, 1e-3) == (None, False))
    check("time to reach: level above the coarsest error is an upper bound",
          time_to_reach(A, 0.5) == (1.0, False))
    rows = pareto_table({"A": A, "B": B}, levels=[1e-2, 5e-3, 1e-3])
    check("pareto: B ahead at 1e-2 by 10/sqrt(10)",
          rows[0]["best"] == "B" and rows[0]["runner_up"] == "A" and close(rows[0]["speedup"], math.sqrt(10.0)))
    check("pareto: only A reaches 5e-3 and 1e-3",
          rows[1]["best"] == "A" and rows[1]["runner_up"] is None and rows[2]["best"] == "A")
    auto = pareto_table({"A": A, "B": B})
    check("pareto: automatic levels span 1e-1 .. 1e-3", [r["level"] for r in auto][0] == 0.1 and
          auto[-1]["level"] == 1e-3)
    check("nice levels between 3e-3 and 0.04", nice_levels(3e-3, 0.04) == [0.02, 0.01, 0.005])
    check("nice levels in a narrow range: 5 geometric 2-digit values",
          nice_levels(4.416e-3, 6.584e-3) == [0.0065, 0.006, 0.0054, 0.0049, 0.0045])
    check("nice levels in a very narrow range", len(nice_levels(4.41e-3, 4.9e-3)) >= 3)
    check("failure message: the sph: error line",
          failure_message("noise\nsph: error: -cfl must be in (0, 1] (got 5)\n", 1) == "-cfl must be in (0, 1] (got 5)")
    check("failure message: a PETSc signal",
          failure_message("[0]PETSC ERROR: Caught signal number 11 SEGV: Segmentation Violation\nx\n", 59)
          .startswith("Caught signal number 11"))
    check("failure message: last line otherwise", failure_message("a\nboom\n", 3) == "exit code 3: boom")
    check("sweep with a mapping value", sweep_choice("ksp", {"ppe_ksp_type": "gmres", "ppe_pc_type": "jacobi"}) ==
          ("gmres+jacobi", {"ppe_ksp_type": "gmres", "ppe_pc_type": "jacobi"}))
    check("options: booleans as 1/0, flags without value",
          option_args({"shifting": False, "-ppe_ksp_monitor": None, "re": 100}) == ["-shifting", "0", "-ppe_ksp_monitor", "-re", "100"])
    check("matrix: failure reason without the step prefix",
          short_reason("step 12 (t = 0.034): non-finite velocity at particle 7") == "non-finite velocity at particle 7")
    check("matrix: long reasons are cut", len(short_reason("x" * 100)) == 61)
    check("matrix: option errors are not 'n/a'", option_problem("-cfl must be in (0, 1] (got 5)") and
          not option_problem("this case is a compressible gas (ideal-gas EOS, energy equation): use -solver compressible, not isph"))
    failed = [n for n, ok in checks if not ok]
    print("self-test: %d of %d checks passed" % (len(checks) - len(failed), len(checks)))
    return 1 if failed else 0
