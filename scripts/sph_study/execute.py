"""Running: one run in its folder (run.json, stderr.txt), up-to-date checks, the one-line failure reason,
the cores other work keeps busy, and every run of a study (one at a time or side by side)."""

import concurrent.futures
import datetime
import os
import re
import shlex
import subprocess
import sys
import threading
import time

from .common import REPO, read_json, write_json
from .metric import check_metric, metric_label, metric_value


def failure_message(stderr, returncode):
    """The one-line reason of a failed run: the program's 'sph: error: ...' line, else a PETSc signal
    line, else the last line of stderr."""
    lines = [l.strip() for l in (stderr or "").splitlines() if l.strip()]
    for l in reversed(lines):
        m = re.search(r"sph: error: (.*)", l)
        if m:
            return m.group(1).strip()
    for l in lines:
        m = re.search(r"PETSC ERROR: (Caught signal.*)", l)
        if m:
            return m.group(1).strip()
    if returncode is not None and returncode < 0:
        return "killed by signal %d" % -returncode
    tail = lines[-1] if lines else ""
    return ("exit code %s" % returncode) + (": " + tail if tail else "")


def up_to_date(run):
    """True when the run folder holds the result of the same sph arguments: a summary.json, or a failure
    recorded in run.json."""
    rec = read_json(os.path.join(run["dir"], "run.json"))
    if not rec or rec.get("args") != run["args"] or rec.get("mpi", 0) != run["mpi"]:
        return False
    if os.path.exists(os.path.join(run["dir"], "summary.json")):
        return True
    return rec.get("status") == "failed"


def busy_cores(window=1.0):
    """Cores kept busy by other work over a short window (from /proc/stat), or the 1-minute load average
    where /proc/stat is missing. Sampled just before a run starts, so that, unlike the load average,
    it does not count the previous run's own threads."""
    def totals():
        with open("/proc/stat") as f:
            cpu = [int(v) for v in f.readline().split()[1:]]
        idle = cpu[3] + (cpu[4] if len(cpu) > 4 else 0)  # idle + iowait
        return sum(cpu), idle
    try:
        t0, i0 = totals()
        time.sleep(window)
        t1, i1 = totals()
    except (OSError, ValueError, IndexError):
        return os.getloadavg()[0]
    return (os.cpu_count() or 1) * (1.0 - (i1 - i0) / max(1, t1 - t0))


_scene_lock = threading.Lock()


def make_scene(scene):
    """Writes a run's scene file (scripts/make-scene's arguments, or the study's own command) unless an
    earlier run made it; returns an error message, or None."""
    with _scene_lock:
        if os.path.exists(scene["file"]):
            return None
        os.makedirs(os.path.dirname(scene["file"]), exist_ok=True)
        if "command" in scene:
            cmd, cwd, what = scene["command"], scene["cwd"], " ".join(scene["command"])
        else:
            cmd = [os.path.join(REPO, "scripts", "make-scene")] + scene["args"] + ["-o", scene["file"]]
            cwd, what = REPO, "make-scene " + " ".join(scene["args"])
        try:
            p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        except OSError as e:
            return "%s failed: %s" % (what, e)
        if p.returncode != 0:
            return "%s failed: %s" % (what, (p.stderr.strip().splitlines() or ["?"])[-1])
        if not os.path.exists(scene["file"]):
            return "%s wrote no %s" % (what, scene["file"])
    return None


def execute(run, timeout, jobs):
    os.makedirs(run["dir"], exist_ok=True)
    for stale in ("summary.json", "run.json"):
        try:
            os.remove(os.path.join(run["dir"], stale))
        except FileNotFoundError:
            pass
    # Runs side by side share the cores: each gets its share as OpenMP threads, not all of them.
    threads = os.environ.get("OMP_NUM_THREADS") or str(max(1, (os.cpu_count() or 1) // (jobs * max(1, run["mpi"]))))
    # The study owns its run folders: a rerun replaces what an earlier one left there.
    command = run["command"] + ["-overwrite"]
    rec = {"command": command, "command_line": " ".join(shlex.quote(c) for c in command),
           "args": run["args"], "mpi": run["mpi"], "jobs": jobs, "cwd": REPO,
           "started": datetime.datetime.now().isoformat(timespec="seconds"), "status": "running",
           "busy_cores_at_start": round(busy_cores() if jobs <= 1 else os.getloadavg()[0], 2),
           "cpus": os.cpu_count(),
           "omp_num_threads": threads}
    write_json(os.path.join(run["dir"], "run.json"), rec)
    env = dict(os.environ, OMP_NUM_THREADS=threads)
    if run["mpi"]:
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
        env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    start = time.time()
    problem = make_scene(run["scene"]) if run.get("scene") else None
    if problem:
        rec.update(status="failed", failure=problem, returncode=None, elapsed_s=0.0)
        write_json(os.path.join(run["dir"], "run.json"), rec)
        return rec
    try:
        p = subprocess.run(command, cwd=REPO, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           text=True, timeout=timeout)
        rc, stdout, stderr = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired as e:
        rc, stdout, stderr = None, e.stdout or "", (e.stderr or "")
        stdout = stdout.decode(errors="replace") if isinstance(stdout, bytes) else stdout
        stderr = (stderr.decode(errors="replace") if isinstance(stderr, bytes) else stderr) + \
            "\nsph: error: timed out after %g s (--timeout)\n" % timeout
    except OSError as e:
        rc, stdout, stderr = 127, "", "sph: error: cannot run %s: %s\n" % (command[0], e)
    rec["elapsed_s"] = round(time.time() - start, 3)
    rec["returncode"] = rc
    with open(os.path.join(run["dir"], "stderr.txt"), "w") as f:
        f.write(stderr)
    if stdout.strip():
        with open(os.path.join(run["dir"], "stdout.txt"), "w") as f:
            f.write(stdout)
    summary = read_json(os.path.join(run["dir"], "summary.json"))
    if rc == 0 and summary and summary.get("status", "completed") == "completed":
        rec["status"] = "completed"
    else:
        rec["status"] = "failed"
        rec["failure"] = (summary or {}).get("failure") or failure_message(stderr, rc)
    write_json(os.path.join(run["dir"], "run.json"), rec)
    return rec


def run_all(runs, jobs, timeout, force, retry_failed, metric):
    todo, skipped = [], []
    for r in runs:
        rec = read_json(os.path.join(r["dir"], "run.json")) or {}
        if not force and up_to_date(r) and not (retry_failed and rec.get("status") == "failed"):
            skipped.append(r)
        else:
            todo.append(r)
    # A metric given in the study file is checked on the first completed run (one already there, else
    # the first to finish): a misspelled name stops the study before it spends hours on runs.
    spec = metric if isinstance(metric, dict) else None
    column = spec if spec and spec["kind"] == "column" else None
    metric = metric_label(metric) if isinstance(metric, dict) else metric
    refusal = [None]
    if spec:
        for r in skipped:
            if (read_json(os.path.join(r["dir"], "summary.json")) or {}).get("status") == "completed":
                refusal[0] = check_metric(spec, r["dir"])
                spec = None
                break
        if refusal[0]:
            sys.exit("study: " + refusal[0])
    lock = threading.Lock()
    done = [0]
    failed = [0]

    def one(r):
        nonlocal spec
        if refusal[0]:
            return
        rec = execute(r, timeout, jobs)
        with lock:
            if spec and rec["status"] != "failed":
                refusal[0] = check_metric(spec, r["dir"])
                spec = None
            done[0] += 1
            if rec["status"] == "failed":
                failed[0] += 1
                what = "FAILED: " + rec["failure"]
            else:
                s = read_json(os.path.join(r["dir"], "summary.json")) or {}
                errs = s.get("errors") or {}
                m = r.get("metric") or metric
                shown = [m] if m in errs else list(errs)[:1]
                what = "%.1f s" % rec["elapsed_s"] + "".join(", %s %.3g" % (k, errs[k]) for k in shown)
                if column and not refusal[0]:
                    v, why = metric_value(column, {"status": "completed", "dir": r["dir"]})
                    what += ", %s %s" % (metric, "%.4g" % v if v is not None else why)
            where = r["label"] if "row" in r else "%s nx=%d" % (r["label"], r["nx"])
            print("[%d/%d] %s: %s" % (done[0], len(todo), where, what), flush=True)

    if todo:
        print("running %d runs (%d at a time)%s" % (len(todo), jobs, ", skipping %d up to date" % len(skipped)
                                                    if skipped else ""), flush=True)
    if jobs <= 1:
        for r in todo:
            one(r)
    else:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            for f in [pool.submit(one, r) for r in todo]:
                f.result()
    if refusal[0]:
        sys.exit("study: " + refusal[0])
    print("ran %d runs (%d failed), skipped %d runs (up to date)" % (len(todo), failed[0], len(skipped)), flush=True)
    return len(todo), len(skipped), failed[0]


def study_settings(a, study):
    """(mpi ranks per run, absolute sph path, study folder) from the command line and the study file."""
    mpi = a.mpi if a.mpi is not None else int(study.get("mpi") or 0)
    sph = os.path.abspath(a.sph)
    out_dir = os.path.abspath(a.out or os.path.join(os.getcwd(), "out", "studies", study["name"]))
    return mpi, sph, out_dir


def carry_out(a, runs, sph, out_dir, metric):
    """--dry-run lists the runs and returns None; otherwise checks the program, makes the study folder and
    runs what is not up to date (nothing with --report-only); returns run_all's counts."""
    if a.dry_run:
        for r in runs:
            print(("skip " if up_to_date(r) else "run  ") + " ".join(shlex.quote(c) for c in r["command"]))
        return None
    if not a.report_only and not os.access(sph, os.X_OK):
        sys.exit("study: no sph executable at %s (build it with scripts/build, or pass --sph PATH)" % sph)
    os.makedirs(out_dir, exist_ok=True)
    return (0, len(runs), 0) if a.report_only else run_all(runs, max(1, a.jobs), a.timeout, a.force, a.retry_failed,
                                                            metric)
