#!/usr/bin/env python3
"""Fixed benchmark workloads for the sph program, timed per phase with PETSc's -log_view.

Each workload runs a fixed number of steps (-max_steps, no frames, no checkpoints, no progress line)
with the log written as CSV (-log_view :FILE:ascii_csv). The events of the "SPH time loop" stage (see
src/core/log_events.hpp) are turned into seconds per particle-step for each phase, next to PETSc's
PCSetUp/KSPSolve, the KSP iterations from summary.json and the child's peak resident memory (getrusage
of that one child).

  bench/run_bench.py --label before                   # default suite: 1e4 and 1e5 particles
  bench/run_bench.py --label before --large           # adds the 1e6-particle workloads (slow)
  bench/run_bench.py --label before --only isph2d     # workloads whose name contains a pattern
  bench/run_bench.py --suite amg --label amg          # BoomerAMG option sets on the ISPH PPE
  bench/run_bench.py --suite ksp --label ksp          # KSP x PC pairs on the ISPH PPE
  bench/run_bench.py --compare before after           # ratios after/before, per workload and phase

Results go to out/bench/<label>/: workloads.csv (one row per workload), phases.csv (one row per
workload and phase), report.md (the same as tables), meta.json (command, commit, dirty files), and
one folder per workload with its log_view.csv, summary.json and stderr. Python 3 standard library only.
"""
import argparse
import csv
import datetime
import json
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
STAGE = "SPH time loop"
COMMON = ["-output_interval", "0", "-checkpoint_interval", "0", "-progress", "0"]
# Set by --ranks/--threads: the launcher in front of the program and the cores a run may use.
LAUNCH = []
CORES_USED = 1

# name, solver label, dim, steps, arguments, when: False (always), True (with --large), "explicit" (only
# when --only names it: gas3d-1e6 needs about 9 GB and a quarter of an hour on 2 cores; a 3D ISPH step at
# 1e6 particles takes minutes). Sizes: nx^2 in 2D, nx^3 for the Beltrami cube; the 3D Sod tube holds
# about nx ny^2 (1 + 1/8) particles. The 3D incompressible workloads are the Beltrami flow, the 3D
# counterpart of Taylor-Green (periodic, no walls); a 3D step costs about 15x a 2D one per particle (about
# 110 neighbours instead of 20), so they take fewer steps.
TGV = ["-case", "taylor_green"]
BELTRAMI = ["-case", "beltrami"]
SOD3 = ["-options_file", "cases/sod.opts", "-dim", "3"]
WORKLOADS = [
    ("isph2d-1e4", "isph", 2, 10, TGV + ["-solver", "isph", "-nx", "100"], False),
    ("isph2d-1e5", "isph", 2, 10, TGV + ["-solver", "isph", "-nx", "316"], False),
    ("isph2d-1e6", "isph", 2, 10, TGV + ["-solver", "isph", "-nx", "1000"], True),
    ("wcsph2d-1e4", "wcsph", 2, 20, TGV + ["-solver", "wcsph", "-nx", "100"], False),
    ("wcsph2d-1e5", "wcsph", 2, 20, TGV + ["-solver", "wcsph", "-nx", "316"], False),
    ("wcsph2d-1e6", "wcsph", 2, 20, TGV + ["-solver", "wcsph", "-nx", "1000"], True),
    # The plain scheme of the fastest published CPU codes (no correction matrices, no consistent
    # Laplacian, no shifting): what the per-core speed target is measured against.
    ("wcsph2d-plain-1e5", "wcsph", 2, 20,
     TGV + ["-solver", "wcsph", "-nx", "316", "-wcsph_operators", "classic", "-shifting", "0"], "explicit"),
    ("wcsph2d-plain-1e6", "wcsph", 2, 20,
     TGV + ["-solver", "wcsph", "-nx", "1000", "-wcsph_operators", "classic", "-shifting", "0"], "explicit"),
    ("isph3d-1e5", "isph", 3, 3, BELTRAMI + ["-solver", "isph", "-nx", "46"], False),
    ("isph3d-1e6", "isph", 3, 2, BELTRAMI + ["-solver", "isph", "-nx", "100"], "explicit"),
    ("wcsph3d-1e5", "wcsph", 3, 10, BELTRAMI + ["-solver", "wcsph", "-nx", "46"], False),
    ("wcsph3d-1e6", "wcsph", 3, 5, BELTRAMI + ["-solver", "wcsph", "-nx", "100"], True),
    ("gas3d-1e5", "compressible", 3, 10, SOD3 + ["-nx", "96", "-ny", "32"], False),
    ("gas3d-1e6", "compressible", 3, 10, SOD3 + ["-nx", "200", "-ny", "64"], "explicit"),
]
# Tiny run whose peak memory is the program's fixed cost (libraries, PETSc, MPI).
BASELINE = ("baseline", TGV + ["-solver", "isph", "-nx", "8", "-max_steps", "1"])

# The BoomerAMG option sets compared on the ISPH pressure solve.
# (tgv512 only when --only names it.)
AMG_CASES = [
    ("tgv128", 10, TGV + ["-solver", "isph", "-nx", "128"]),
    ("tgv128-disordered", 10, TGV + ["-solver", "isph", "-nx", "128", "-perturbation", "0.2"]),
    ("tgv256", 10, TGV + ["-solver", "isph", "-nx", "256"]),
    ("cavity50", 20, ["-case", "lid_driven_cavity", "-solver", "isph", "-nx", "50"]),
    ("beltrami40", 5, BELTRAMI + ["-solver", "isph", "-nx", "40"]),
    ("tgv512", 5, TGV + ["-solver", "isph", "-nx", "512"]),
]
HMIS = ["-ppe_pc_hypre_boomeramg_coarsen_type", "HMIS", "-ppe_pc_hypre_boomeramg_interp_type", "ext+i"]
PMIS = ["-ppe_pc_hypre_boomeramg_coarsen_type", "PMIS", "-ppe_pc_hypre_boomeramg_interp_type", "ext+i"]
THETA = "-ppe_pc_hypre_boomeramg_strong_threshold"
RELAX = "-ppe_pc_hypre_boomeramg_relax_type_all"  # smoother on every level (default: hybrid symmetric Gauss-Seidel)
AMG_SETS = [
    ("default", []),
    ("hmis-ei-0.5", HMIS + [THETA, "0.5"]),
    ("hmis-ei-0.25", HMIS + [THETA, "0.25"]),
    ("pmis-ei-0.5", PMIS + [THETA, "0.5"]),
    ("pmis-ei-0.25", PMIS + [THETA, "0.25"]),
    ("hmis-ei-0.5-agg1", HMIS + [THETA, "0.5", "-ppe_pc_hypre_boomeramg_agg_nl", "1"]),
    ("hmis-ei-0.5-pmax4", HMIS + [THETA, "0.5", "-ppe_pc_hypre_boomeramg_P_max", "4"]),
    ("falgout-0.5", [THETA, "0.5"]),
    ("falgout-agg1", ["-ppe_pc_hypre_boomeramg_agg_nl", "1"]),
    ("chebyshev", [RELAX, "Chebyshev"]),
    ("l1-jacobi", [RELAX, "l1scaled-Jacobi"]),
    ("l1-sor", [RELAX, "l1scaled-SOR/Jacobi"]),
]

# Phases of the table: (column, events added up). Nested events are left out of the sum that makes
# "other" (SPHNbrRebuild is part of SPHNbrUpdate; PCSetUp and KSPSolve are parts of SPHPPESolve).
PHASES = [
    ("neighbours", ["SPHNbrUpdate"]),
    ("  rebuild", ["SPHNbrRebuild"]),
    ("density", ["SPHDensity"]),
    ("gas density/h", ["SPHGasDensityH"]),
    ("gas pair lists", ["SPHGasPairs"]),
    ("forces", ["SPHForces"]),
    ("ppe assembly", ["SPHPPEAssembly"]),
    ("ppe solve", ["SPHPPESolve"]),
    ("  PCSetUp", ["PCSetUp"]),
    ("  KSPSolve", ["KSPSolve"]),
    ("shifting", ["SPHShifting"]),
]
TOP_LEVEL = ["SPHNbrUpdate", "SPHDensity", "SPHGasDensityH", "SPHGasPairs", "SPHForces", "SPHPPEAssembly",
             "SPHPPESolve", "SPHShifting"]


def parse_log_csv(path):
    """{stage name: {"time": s, "events": {event: (count, time s)}}} from a -log_view ascii_csv file.

    The file has a row per stage, event and rank (the stage's own row is the event "summary"). The figures
    are those of PETSc's text summary: a stage's time is its mean over the ranks, an event's count and time
    their maxima, and events that no rank ran are left out."""
    stages = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            stage = stages.setdefault(row["Stage Name"].strip(), {"times": [], "events": {}})
            # Some of PETSc's names are padded with blanks ("VecScatterEnd  ").
            name, count, seconds = row["Event Name"].strip(), int(row["Count"]), float(row["Time"])
            if name == "summary":
                stage["times"].append(seconds)
            elif count > 0:
                c, t = stage["events"].get(name, (0, 0.0))
                stage["events"][name] = (max(c, count), max(t, seconds))
    return {name: {"time": sum(s["times"]) / len(s["times"]) if s["times"] else 0.0, "events": s["events"]}
            for name, s in stages.items()}


def git_state():
    def out(*args):
        try:
            return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True).stdout
        except (OSError, subprocess.CalledProcessError):
            return ""
    dirty = [l[3:] for l in out("status", "--porcelain", "--untracked-files=no").splitlines() if len(l) > 3]
    return {"commit": out("rev-parse", "--short", "HEAD").strip(), "dirty_files": dirty}


def run_child(cmd, stderr_path, env):
    """Runs cmd; returns (exit code, wall seconds, CPU seconds, peak RSS in bytes) of that child alone."""
    start = time.monotonic()
    with open(stderr_path, "w") as err:
        p = subprocess.Popen(cmd, cwd=ROOT, stdout=err, stderr=subprocess.STDOUT, env=env)
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status) if hasattr(os, "waitstatus_to_exitcode") else status
    cpu = usage.ru_utime + usage.ru_stime
    return p.returncode, time.monotonic() - start, cpu, usage.ru_maxrss * 1024  # ru_maxrss: KiB on Linux


def run_workload(sph, args, steps, folder, env, extra=()):
    """One run; returns a dict of its figures, or raises RuntimeError."""
    if os.path.isdir(folder):
        shutil.rmtree(folder)
    os.makedirs(folder)
    log = os.path.join(folder, "log_view.csv")
    out_dir = os.path.join(folder, "run")
    cmd = [*LAUNCH, sph, *args, "-max_steps", str(steps), *COMMON, *extra, "-output_dir", out_dir, "-log_view", f":{log}:ascii_csv"]
    rc, wall, cpu, rss = run_child(cmd, os.path.join(folder, "stderr.txt"), env)
    if rc != 0:
        with open(os.path.join(folder, "stderr.txt")) as f:
            tail = f.read()[-2000:]
        raise RuntimeError(f"exit {rc}: {' '.join(cmd)}\n{tail}")
    with open(os.path.join(out_dir, "summary.json")) as f:
        summary = json.load(f)
    shutil.copy(os.path.join(out_dir, "summary.json"), os.path.join(folder, "summary.json"))
    shutil.rmtree(out_dir)  # the frames are not needed
    stages = parse_log_csv(log)
    if STAGE not in stages:
        raise RuntimeError(f"no '{STAGE}' stage in {log}: is the program built with the SPH log events?")
    loop = stages[STAGE]
    ev = loop["events"]
    ksp = summary.get("ksp", {})
    return {"command": " ".join(cmd), "n": int(summary["n_particles"]), "steps": int(summary["steps"]),
            "wall_s": wall, "cpu_s": cpu, "rss": rss, "loop_s": loop["time"], "events": {k: v for k, v in ev.items()},
            "ksp_its_mean": ksp.get("iterations_mean", ""), "ksp_its_max": ksp.get("iterations_max", ""),
            "status": summary.get("status", "")}


def event_time(r, name):
    return r["events"].get(name, (0, 0.0))[1]


def figures(r):
    """Per-particle-step figures of one run."""
    ps = r["n"] * r["steps"]
    step = event_time(r, "SPHStep")
    f = {"loop": r["loop_s"] / ps, "step": step / ps}
    for col, events in PHASES:
        f[col.strip()] = sum(event_time(r, e) for e in events) / ps
    f["other"] = (step - sum(event_time(r, e) for e in TOP_LEVEL)) / ps
    f["diagnostics"] = event_time(r, "SPHDiagnostics") / ps
    ppe = event_time(r, "SPHPPEAssembly") + event_time(r, "SPHPPESolve")
    f["ppe_fraction"] = ppe / step if step > 0 else 0.0
    rebuilds = r["events"].get("SPHNbrRebuild", (0, 0.0))[0]
    f["rebuilds_per_step"] = rebuilds / r["steps"]
    f["rebuild_s_per_particle"] = event_time(r, "SPHNbrRebuild") / (rebuilds * r["n"]) if rebuilds else 0.0
    return f


PHASE_COLUMNS = ["step", "neighbours", "rebuild", "density", "gas density/h", "gas pair lists", "forces",
                 "ppe assembly", "ppe solve", "PCSetUp", "KSPSolve", "shifting", "other", "diagnostics", "loop"]


def fmt(x, spec=".3g"):
    return format(x, spec) if isinstance(x, (int, float)) else str(x)


def write_default_results(folder, results, baseline_rss, meta):
    rows, phase_rows = [], []
    for name, solver, dim, r in results:
        f = figures(r)
        extra_rss = r["rss"] - baseline_rss if baseline_rss else r["rss"]
        rows.append({
            "workload": name, "solver": solver, "dim": dim, "n_particles": r["n"], "steps": r["steps"],
            "wall_s": round(r["wall_s"], 3), "cpu_over_wall": round(r.get("cpu_s", 0.0) / (r["wall_s"] * CORES_USED), 3),
            "loop_s_per_ps": f["loop"], "step_s_per_ps": f["step"],
            "ppe_fraction": round(f["ppe_fraction"], 4) if solver == "isph" else "",
            "ksp_its_mean": r["ksp_its_mean"], "ksp_its_max": r["ksp_its_max"],
            "pcsetup_s_per_ps": f["PCSetUp"] if solver == "isph" else "",
            "kspsolve_s_per_ps": f["KSPSolve"] if solver == "isph" else "",
            "rebuilds_per_step": f["rebuilds_per_step"], "rebuild_s_per_particle": f["rebuild_s_per_particle"],
            "peak_rss_mib": round(r["rss"] / 2**20, 1),
            "bytes_per_particle": round(extra_rss / r["n"]), "status": r["status"], "date": r.get("date", ""),
            "commit": r.get("git", {}).get("commit", "")})
        for col in PHASE_COLUMNS:
            phase_rows.append({"workload": name, "solver": solver, "dim": dim, "n_particles": r["n"],
                               "steps": r["steps"], "phase": col, "s_per_particle_step": f[col],
                               "fraction_of_step": round(f[col] / f["step"], 4) if f["step"] else ""})
    write_csv(os.path.join(folder, "workloads.csv"), rows)
    write_csv(os.path.join(folder, "phases.csv"), phase_rows)

    md = [f"# Benchmark `{meta['label']}`", "",
          f"Last run {meta['date']}, commit {meta['git']['commit']}"
          + (f" with uncommitted changes in {', '.join(meta['git']['dirty_files'])}" if meta["git"]["dirty_files"] else "")
          + f", {meta['cpus']} CPUs, {meta.get('ranks', 1)} MPI rank(s) x OMP_NUM_THREADS={meta['omp_num_threads']}. Times in seconds per particle-step "
          "(event time over steps x particles) within the time-loop stage; PETSc events are inclusive "
          "(rebuild is part of neighbours; PCSetUp and KSPSolve are parts of ppe solve); other = step minus its "
          "top-level phases (integration loops, halo exchanges of fields, dt).", ""]
    names = [r[0] for r in results]
    md.append("| phase | " + " | ".join(names) + " |")
    md.append("|---|" + "---:|" * len(names))
    by = {r[0]: figures(r[3]) for r in results}
    for col in PHASE_COLUMNS:
        vals = [by[n][col] for n in names]
        if all(v == 0 for v in vals):
            continue
        md.append(f"| {col} | " + " | ".join(fmt(v) for v in vals) + " |")
    md += ["", "| workload | N | steps | step s/ps | PPE fraction | KSP its mean (max) | PCSetUp s/ps | KSPSolve s/ps | "
           "rebuilds/step | s per particle and rebuild | peak RSS MiB | bytes/particle | CPU/wall |",
           "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for row in rows:
        its = f"{fmt(row['ksp_its_mean'])} ({row['ksp_its_max']})" if row["ksp_its_mean"] != "" else ""
        md.append(f"| {row['workload']} | {row['n_particles']} | {row['steps']} | {fmt(row['step_s_per_ps'])} | "
                  f"{fmt(row['ppe_fraction'])} | {its} | {fmt(row['pcsetup_s_per_ps'])} | "
                  f"{fmt(row['kspsolve_s_per_ps'])} | {fmt(row['rebuilds_per_step'], '.2f')} | "
                  f"{fmt(row['rebuild_s_per_particle'])} | {row['peak_rss_mib']} | "
                  f"{row['bytes_per_particle']} | {row['cpu_over_wall']} |")
    md += ["", f"bytes/particle = (peak RSS - {baseline_rss / 2**20:.1f} MiB of a {BASELINE[1][-3]}^2-particle run) / N. "
           "CPU/wall: the run's CPU time over its wall time and the cores it used (ranks x threads); well below 1 means it shared its cores with other work, or its threads waited "
           "(its times are inflated).", ""]
    # Scaling in N: each phase's s/ps at the largest size over the smallest, per family of workloads
    # (the name without its size: wcsph2d-plain-1e5 and -1e6 are one family, wcsph2d-1e5 another),
    # 1 = linear.
    groups = {}
    for name, solver, dim, r in results:
        groups.setdefault(name.rsplit("-", 1)[0], []).append((r["n"], name))
    scal = []
    for family, runs in groups.items():
        if len(runs) < 2:
            continue
        runs.sort()
        (n0, a), (n1, b) = runs[0], runs[-1]
        ratios = [f"{col} {by[b][col] / by[a][col]:.2f}" for col in PHASE_COLUMNS if by[a][col] > 0 and by[b][col] > 0]
        scal.append(f"- {family}, N {n0} -> {n1}: s/ps ratio " + ", ".join(ratios))
    if scal:
        md += ["Scaling (s per particle-step at the largest N over the smallest; 1.00 = linear in N):", ""] + scal + [""]
    with open(os.path.join(folder, "report.md"), "w") as f:
        f.write("\n".join(md))
    return "\n".join(md)


def write_csv(path, rows):
    if not rows:
        return
    with open(path, "w", newline="") as f:
        fields = list(dict.fromkeys(k for r in rows for k in r))  # failed runs' rows carry other columns
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        w.writerows(rows)


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def compare(out_root, a, b):
    pa, pb = (read_csv(os.path.join(out_root, x, "phases.csv")) for x in (a, b))
    key = lambda r: (r["workload"], r["phase"])
    ia = {key(r): float(r["s_per_particle_step"]) for r in pa}
    ib = {key(r): float(r["s_per_particle_step"]) for r in pb}
    workloads = sorted({k[0] for k in ia} & {k[0] for k in ib})
    if not workloads:
        sys.exit(f"no workload in common between {a} and {b}")
    print(f"{'workload':<14} {'phase':<16} {a:>12} {b:>12} {b + '/' + a:>12}")
    for w in workloads:
        for col in PHASE_COLUMNS:
            x, y = ia.get((w, col), 0.0), ib.get((w, col), 0.0)
            if x == 0 and y == 0:
                continue
            ratio = f"{y / x:.3f}" if x > 0 else "-"
            print(f"{w:<14} {col:<16} {x:>12.3e} {y:>12.3e} {ratio:>12}")
    wa = {r["workload"]: r for r in read_csv(os.path.join(out_root, a, "workloads.csv"))}
    wb = {r["workload"]: r for r in read_csv(os.path.join(out_root, b, "workloads.csv"))}
    print(f"\n{'workload':<14} {'peak RSS MiB':>24} {'KSP its mean':>24}")
    for w in workloads:
        if w in wa and w in wb:
            print(f"{w:<14} {wa[w]['peak_rss_mib']:>11} {wb[w]['peak_rss_mib']:>12} "
                  f"{wa[w]['ksp_its_mean']:>11} {wb[w]['ksp_its_mean']:>12}")


# The Krylov method and preconditioner pairs compared on the ISPH pressure solve (--suite ksp).
KSP_CASES = [c for c in AMG_CASES if c[0] in ("tgv128", "tgv256", "cavity50")]
KSP_SETS = [
    ("default", []),  # GMRES (right-preconditioned) + BoomerAMG
    ("gamg", ["-ppe_pc_type", "gamg"]),
    ("ilu-gmres", ["-ppe_ksp_type", "gmres", "-ppe_pc_type", "ilu"]),
    ("bjacobi-ilu", ["-ppe_pc_type", "bjacobi", "-ppe_sub_pc_type", "ilu"]),
    ("jacobi-cg", ["-ppe_ksp_type", "cg", "-ppe_pc_type", "jacobi"]),
    ("jacobi-gmres", ["-ppe_ksp_type", "gmres", "-ppe_pc_type", "jacobi"]),
]


# The pressure solve's PETSc options carry the prefix ppe_ (-ppe_ksp_type, -ppe_pc_type); a program
# built before they took it reads them unprefixed (-ksp_type) and refuses the new names, as a newer
# one refuses the old. The option sets above are spelled the new way. So that a build of an older
# commit can be timed beside a newer one (--sph OLD --label before, then --compare), each program is
# asked once which spelling it takes: one whose -help does not list -ppe_ksp_type gets the sets with
# the prefix taken off again. -ppe_pc_drop_tol had its name before the prefix came and keeps it.
PPE_PREFIXED = ("-ppe_ksp_", "-ppe_pc_", "-ppe_sub_", "-ppe_mg_")
PPE_NAMED_BEFORE = ("-ppe_pc_drop_tol",)
_takes_ppe_prefix = {}


def takes_ppe_prefix(sph, env):
    if sph not in _takes_ppe_prefix:
        help_text = subprocess.run([sph, "-help"], cwd=ROOT, capture_output=True, text=True, env=env).stdout
        _takes_ppe_prefix[sph] = "-ppe_ksp_type" in help_text
    return _takes_ppe_prefix[sph]


def spelled_for(sph, env, opts):
    """The options as the program at sph spells them (see PPE_PREFIXED)."""
    if takes_ppe_prefix(sph, env):
        return list(opts)
    return ["-" + o[len("-ppe_"):] if o.startswith(PPE_PREFIXED) and o not in PPE_NAMED_BEFORE else o
            for o in opts]


def failure_line(err):
    """The program's one-line error from a failed run's RuntimeError."""
    lines = [l for l in str(err).splitlines() if l.startswith("sph: error:")]
    return lines[-1][len("sph: error: "):] if lines else str(err).splitlines()[0]


def run_sets(args, folder, env, cases, sets, name, title):
    """Each case under each option set; writes <name>.csv and <name>.md."""
    rows = []
    for case, steps, cargs in cases:
        if args.only and not any(p in case for p in args.only):
            continue
        if case == "tgv512" and not (args.only and case in args.only):
            continue
        for set_name, opts in sets:
            if args.sets and set_name not in args.sets and set_name != "default":
                continue
            best = None
            for k in range(args.repeat):
                sub = os.path.join(folder, f"{case}-{set_name}-{k}")
                try:
                    r = run_workload(args.sph, cargs, steps, sub, env, spelled_for(args.sph, env, opts))
                except RuntimeError as e:  # e.g. a solve that does not converge: recorded, the suite goes on
                    print(f"  {case} {set_name}: failed: {failure_line(e)}", flush=True)
                    rows.append({"case": case, "options": set_name, "failure": failure_line(e)})
                    break
                ps_steps = r["steps"]
                m = {"ksp_its_mean": r["ksp_its_mean"], "ksp_its_max": r["ksp_its_max"],
                     "pcsetup_s": event_time(r, "PCSetUp") / ps_steps, "kspsolve_s": event_time(r, "KSPSolve") / ps_steps,
                     "ppe_solve_s": event_time(r, "SPHPPESolve") / ps_steps, "step_s": event_time(r, "SPHStep") / ps_steps}
                # Each time: the minimum over the repeats (the machine is shared).
                best = m if best is None else {key: min(best[key], m[key]) if key.endswith("_s") else m[key] for key in m}
                print(f"  {case} {set_name} #{k + 1}: its {m['ksp_its_mean']:.1f}  PCSetUp {m['pcsetup_s']:.4f}  "
                      f"KSPSolve {m['kspsolve_s']:.4f}  step {m['step_s']:.4f} s", flush=True)
            if best is None:
                continue
            rows.append({"case": case, "n_particles": r["n"], "steps": ps_steps, "options": set_name,
                         "ksp_its_mean": best["ksp_its_mean"], "ksp_its_max": best["ksp_its_max"],
                         "pcsetup_s_per_step": best["pcsetup_s"], "kspsolve_s_per_step": best["kspsolve_s"],
                         "ppe_solve_s_per_step": best["ppe_solve_s"], "step_s_per_step": best["step_s"]})
    write_csv(os.path.join(folder, f"{name}.csv"), rows)
    md = [f"# {title} (min of {args.repeat} runs per time; seconds per step)", "",
          "| case | N | options | KSP its mean (max) | PCSetUp | KSPSolve | PPE solve | PPE solve vs default | step |",
          "|---|---:|---|---:|---:|---:|---:|---:|---:|"]
    default_ppe = {r["case"]: r["ppe_solve_s_per_step"] for r in rows if r["options"] == "default" and "failure" not in r}
    for r in rows:
        if "failure" in r:
            md.append(f"| {r['case']} | | {r['options']} | failed: {r['failure']} | | | | | |")
            continue
        rel = r["ppe_solve_s_per_step"] / default_ppe[r["case"]] if r["case"] in default_ppe else float("nan")
        md.append(f"| {r['case']} | {r['n_particles']} | {r['options']} | {r['ksp_its_mean']:.1f} ({r['ksp_its_max']}) | "
                  f"{r['pcsetup_s_per_step']:.4f} | {r['kspsolve_s_per_step']:.4f} | {r['ppe_solve_s_per_step']:.4f} | "
                  f"{rel:.2f} | {r['step_s_per_step']:.4f} |")
    md += ["", "PPE solve = PCSetUp + KSPSolve + the copies around them; step also holds the phases the options do "
           "not touch, so it carries more of the machine's noise.", ""]
    md += ["Option sets:", ""]
    md += [f"- `{n}`: `{' '.join(o) or '(the program defaults)'}`" for n, o in sets]
    with open(os.path.join(folder, f"{name}.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--label", help="results folder name under the output root (default: the git commit)")
    ap.add_argument("--sph", default=os.path.join(ROOT, "build", "sph"), help="the program (default build/sph)")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench"), help="output root (default out/bench)")
    ap.add_argument("--suite", choices=["default", "amg", "ksp"], default="default")
    ap.add_argument("--large", action="store_true", help="add the 1e6-particle workloads (minutes each on 2 cores)")
    ap.add_argument("--only", nargs="+", metavar="PATTERN", help="workloads (or AMG cases) whose name contains one")
    ap.add_argument("--repeat", type=int, help="runs per workload; the fastest time-loop is kept "
                    "(default 1; the amg suite: 3, each time the minimum)")
    ap.add_argument("--sets", nargs="+", metavar="NAME", help="amg suite: these option sets (and the default)")
    ap.add_argument("--threads", type=int, help="OpenMP threads per rank (sets OMP_NUM_THREADS; default: its value, else 1)")
    ap.add_argument("--ranks", type=int, default=1, help="MPI ranks (runs under mpiexec -n RANKS; default 1, no mpiexec)")
    ap.add_argument("--compare", nargs=2, metavar=("A", "B"), help="print B/A ratios of two earlier labels and exit")
    ap.add_argument("--list", action="store_true", help="list the workloads and exit")
    args = ap.parse_args()

    if args.compare:
        compare(args.out, *args.compare)
        return
    if args.list:
        for name, solver, dim, steps, wargs, large in WORKLOADS:
            when = {True: "(--large) ", "explicit": "(--only NAME) "}.get(large, "")
            print(f"{name:<12} {steps:>3} steps {when}{' '.join(wargs)}")
        for case, steps, cargs in AMG_CASES:
            print(f"amg {case:<18} {steps:>3} steps {' '.join(cargs)}")
        return
    args.sph = os.path.abspath(args.sph)
    if not os.access(args.sph, os.X_OK):
        sys.exit(f"no program at {args.sph}: build it first, or pass --sph")
    args.repeat = args.repeat or (3 if args.suite in ("amg", "ksp") else 1)
    git = git_state()
    label = args.label or (git["commit"] or "current") + ("-dirty" if git["dirty_files"] else "")
    folder = os.path.join(args.out, label)
    os.makedirs(folder, exist_ok=True)
    env = dict(os.environ)
    env.setdefault("OMP_NUM_THREADS", "1")
    if args.threads:
        env["OMP_NUM_THREADS"] = str(args.threads)
    global LAUNCH, CORES_USED
    CORES_USED = args.ranks * int(env["OMP_NUM_THREADS"])
    if args.ranks > 1:
        # Open MPI binds each of up to 2 ranks to one core: threads then need --bind-to none.
        LAUNCH = ["mpiexec", "-n", str(args.ranks)] + (["--bind-to", "none"] if CORES_USED > args.ranks else [])
        env.update({"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
                    "OMPI_MCA_rmaps_base_oversubscribe": "1"})
    meta = {"label": label, "suite": args.suite, "date": datetime.datetime.now().isoformat(timespec="seconds"),
            "argv": sys.argv[1:], "git": git, "sph": args.sph,
            "sph_built": datetime.datetime.fromtimestamp(os.path.getmtime(args.sph)).isoformat(timespec="seconds"), "cpus": os.cpu_count(), "omp_num_threads": env["OMP_NUM_THREADS"], "ranks": args.ranks,
            "load_average_at_start": os.getloadavg()}
    runs_path = os.path.join(folder, "meta.json")
    runs = []
    if os.path.exists(runs_path):
        with open(runs_path) as f:
            runs = json.load(f).get("runs", [])
    with open(runs_path, "w") as f:
        json.dump({"runs": runs + [meta]}, f, indent=2)

    if args.suite == "amg":
        run_sets(args, folder, env, AMG_CASES, AMG_SETS, "amg", "BoomerAMG option sets")
        return
    if args.suite == "ksp":
        run_sets(args, folder, env, KSP_CASES, KSP_SETS, "ksp", "Krylov method and preconditioner")
        return

    baseline = run_workload(args.sph, BASELINE[1], 1, os.path.join(folder, BASELINE[0]), env)
    ran = 0
    for name, solver, dim, steps, wargs, large in WORKLOADS:
        if large == "explicit" and not (args.only and name in args.only):
            continue
        if large is True and not args.large:
            continue
        if args.only and not any(p in name for p in args.only):
            continue
        best = None
        for k in range(args.repeat):
            print(f"{name} ({k + 1}/{args.repeat}) ...", end=" ", flush=True)
            sub = os.path.join(folder, name if args.repeat == 1 else f"{name}-{k + 1}")
            r = run_workload(args.sph, wargs, steps, sub, env)
            print(f"N {r['n']}, {r['steps']} steps, {r['wall_s']:.1f} s wall, "
                  f"{figures(r)['step']:.3g} s per particle-step", flush=True)
            if best is None or r["loop_s"] < best["loop_s"]:
                best = r
        best["date"], best["git"] = meta["date"], meta["git"]
        with open(os.path.join(folder, name + ".json"), "w") as f:
            json.dump(best, f, indent=1)
        ran += 1
    if not ran:
        sys.exit("no workload selected")
    # The label's report covers every workload run under it so far (a rerun replaces its own).
    results = []
    for name, solver, dim, *_ in WORKLOADS:
        path = os.path.join(folder, name + ".json")
        if os.path.exists(path):
            with open(path) as f:
                results.append((name, solver, dim, json.load(f)))
    print()
    print(write_default_results(folder, results, baseline["rss"], meta))
    print(f"\nwritten to {folder}")


if __name__ == "__main__":
    main()
