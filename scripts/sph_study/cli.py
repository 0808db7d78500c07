# Argument parsing and main of scripts/study. The docstring below is its -h text: the user
# documentation of study files.
"""Convergence studies and speed-against-error reports: one command from a study file to tables and plots.

    scripts/study cases/studies/taylor_green.yaml [-j N] [--mpi N] [--sph PATH] [--out DIR]

A study file (YAML, or JSON when it ends in .json) names a case, the solvers, the resolutions (-nx) and
the options; every combination of solver x sweep values x resolution is run with the sph program, each
into its own folder under the study folder (default out/studies/<name>/ in the current folder). Then results.csv,
report.md and the plots (PNG, and PDF beside each) are written there. Study file keys:

    name: taylor_green_re100          # study folder name (default: the file's stem)
    case: taylor_green
    solvers: [isph, wcsph]
    resolutions: [32, 64, 128, 256]   # -nx values
    options: {re: 100, t_end: 1}      # fixed options for every run (key without the leading '-')
    sweeps:                           # optional: every combination is run, for every solver
      shifting: [1, 0]
    solver_options:                   # optional: fixed options of one solver only
      wcsph: {c0_factor: 10}
    solver_sweeps:                    # optional: sweeps of one solver only (e.g. KSP/PC for ISPH)
      isph:
        ksp: [{ppe_ksp_type: cg, ppe_pc_type: hypre}, {ppe_ksp_type: gmres, ppe_pc_type: jacobi}]
    resolution_options:               # optional: options refined with h, one value per resolution
      c0_factor: [10, 20, 40]         #   (in the order of 'resolutions'), for every solver
    solver_resolution_options:        # optional: the same, for one solver only
      wcsph: {delta: [0.1, 0.025, 0.00625]}
    metric: l1_velocity               # error norm of the plots and the Pareto ranking, or a reduction of a
                                      # timeseries.csv column over a window (mean, rms, max, min, integral,
                                      # period, amplitude), with a Richardson estimate per solver:
    # metric: {column: force_baffle_x, reduce: integral, from: 0, to: 1}
    levels: [1e-3, 3e-4]              # optional: the error levels of the speed table (default: 1-2-5 steps)
    mpi: 1                            # optional default for --mpi

A scene of one's own at several resolutions: 'scene:' instead of 'case:', and each resolution runs
-case scene on a file made for it (in <study folder>/scenes/, made once):

    scene: [falling_block, --obstacle-shape, wedge]      # scripts/make-scene's arguments (it adds --nx, -o)
    scene: {command: [./my_scene.py, --nx, "{nx}", -o, "{file}"]}   # or a program of one's own, run in the
                                                         # study file's folder ('{nx}', '{file}' filled in)

Relative paths in a study file (the scene's command, a scene_file option) are the study file's folder's.

A sweep value that is a mapping sets several options at once (its optional 'label' key names it).
An option value null sets a flag without a value. Runs are skipped when their folder holds a
summary.json (or a recorded failure) from the same sph arguments (run.json); --force reruns them.
Without matplotlib the tables are still written (plots are skipped with a message).

A stability matrix replaces case/solvers/resolutions by 'matrix:' (see cases/studies/stability.yaml):

    matrix:
      rows:      # cases: label, case, options, metric, solver_options {solver: {...}} (that solver only)
        - {label: "TGV Re 1000", case: taylor_green, options: {nx: 32, re: 1000, t_end: 5}, metric: l1_velocity}
      columns:   # scheme variants: label, solver, options
        - {label: "WCSPH no delta-SPH", solver: wcsph, options: {density_diffusion: none}}
      options: {}   # optional: every cell

Every (row, column) cell is run once; matrix.csv and matrix.md say for each: ok (metric, wall time),
failed (during time stepping: why), n/a (the program refused the case with that solver at start-up).
"""

import argparse
import os
import sys

from .common import REPO
from .execute import carry_out, study_settings
from .matrix import main_matrix
from .plan import load_study, plan_runs
from .report import make_outputs
from .selftest import self_test


def main(argv=None):
    """scripts/study [argv]: plan, run and report a study (argv: the arguments, default sys.argv[1:])."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="\n\n".join(__doc__.split("\n\n")[2:]))
    ap.add_argument("study", nargs="?", help="study file (.yaml/.yml or .json)")
    ap.add_argument("-j", "--jobs", type=int, default=1, help="runs at a time (default 1: wall times comparable)")
    ap.add_argument("--mpi", type=int, default=None, help="MPI ranks per run (mpirun -n N ...); default: the "
                    "study's 'mpi', else no mpirun")
    ap.add_argument("--sph", default=os.path.join(REPO, "build", "sph"), help="sph executable (default <repo>/build/sph)")
    ap.add_argument("--out", default=None, help="study folder (default out/studies/<name> in the current folder)")
    ap.add_argument("--nx", type=int, nargs="+", default=None, metavar="NX",
                    help="run these resolutions instead of the study's (e.g. --nx 32 64 128)")
    ap.add_argument("--force", action="store_true", help="rerun runs that are up to date")
    ap.add_argument("--retry-failed", action="store_true", help="rerun runs recorded as failed")
    ap.add_argument("--report-only", action="store_true", help="only rebuild results.csv, report.md and plots")
    ap.add_argument("--dry-run", action="store_true", help="print the commands, run nothing")
    ap.add_argument("--timeout", type=float, default=None, help="seconds after which a run is stopped (failed)")
    ap.add_argument("--self-test", action="store_true", help="check the order and Pareto computations and exit")
    a = ap.parse_args(argv)
    if a.self_test:
        return self_test()
    if not a.study:
        ap.error("a study file is needed (or --self-test)")
    if not os.path.exists(a.study):
        ap.error("no study file %s" % a.study)
    try:
        study = load_study(a.study)
    except (TypeError, ValueError, AttributeError, KeyError) as e:  # a wrong type no check above named
        sys.exit("study: %s: a key holds a value of the wrong type (%s: %s); see the keys in scripts/study --help"
                 % (a.study, type(e).__name__, e))
    if "matrix" in study:
        return main_matrix(a, study)
    if a.nx:
        # Any resolutions, unless the study refines options with h: those have one value per listed one.
        missing = sorted(set(a.nx) - set(study["resolutions"]))
        if missing and (study["resolution_options"] or study["solver_resolution_options"]):
            ap.error("--nx %s: not among the study's resolutions %s, which its resolution options follow" %
                     (missing, study["resolutions"]))
        keep = [i for i, nx in enumerate(study["resolutions"]) if nx in a.nx]
        for table in [study["resolution_options"]] + list(study["solver_resolution_options"].values()):
            for key in table:
                table[key] = [table[key][i] for i in keep]
        study["resolutions"] = sorted(set(a.nx))
    mpi, sph, out_dir = study_settings(a, study)
    runs = plan_runs(study, out_dir, sph, mpi)
    # A metric the study file names is checked against the first completed run; the default one is not.
    counts = carry_out(a, runs, sph, out_dir, study["metric_spec"] if study["metric_given"] else study["metric"])
    if counts is None:
        return 0
    make_outputs(study, a.study, runs, out_dir, counts, max(1, a.jobs), mpi)
    print("wrote %s" % os.path.join(out_dir, "report.md"))
    ran, skipped, failed = counts
    if ran and failed == ran and not skipped:  # nothing to report on: a script must not read it as success
        print("study: every run failed (their failures are in report.md and each run's stderr.txt)", file=sys.stderr)
        return 1
    return 0
