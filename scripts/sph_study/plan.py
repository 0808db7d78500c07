"""Study file -> list of runs: loading and checking the study file (both forms, convergence study and
stability matrix), the sph options of every run, its folder and its command line."""

import itertools
import json
import os
import re
import sys

from .metric import metric_label, parse_metric


def load_study(path):
    with open(path) as f:
        text = f.read()
    if path.endswith(".json"):
        try:
            study = json.loads(text)
        except ValueError as e:
            sys.exit("study: %s: not valid JSON (%s); fix the file" % (path, e))
    else:
        try:
            import yaml
        except ImportError:
            sys.exit("study: PyYAML is needed for YAML study files (Debian: apt-get install python3-yaml; "
                     "run the script with /usr/bin/python3)")
        try:
            study = yaml.safe_load(text)
        except yaml.YAMLError as e:
            where = getattr(e, "problem_mark", None)
            sys.exit("study: %s:%s not valid YAML (%s); fix the file" % (
                path, " line %d:" % (where.line + 1) if where else "", getattr(e, "problem", None) or e))
    if not isinstance(study, dict):
        sys.exit("study: %s: expected a mapping at the top level" % path)
    if "matrix" in study:
        return load_matrix(study, path)
    known = {"name", "case", "solvers", "solver", "resolutions", "options", "sweeps", "solver_options",
             "solver_sweeps", "resolution_options", "solver_resolution_options", "metric", "levels", "mpi",
             "description", "scene"}
    unknown = sorted(set(study) - known)
    if unknown:
        sys.exit("study: %s: unknown key(s) %s (known: %s)" % (path, ", ".join(unknown), ", ".join(sorted(known))))
    load_scene(study, path)
    for key in ("case", "resolutions"):
        if key not in study:
            sys.exit("study: %s: missing '%s'" % (path, key))
    solvers = study.get("solvers", study.get("solver"))
    if solvers is None:
        sys.exit("study: %s: missing 'solvers'" % path)
    check_types(study, path, solvers)
    study["solvers"] = [solvers] if isinstance(solvers, str) else list(solvers)
    given = [int(n) for n in study["resolutions"]]
    order = sorted(range(len(given)), key=lambda i: given[i])
    study["resolutions"] = [given[i] for i in order]
    study.setdefault("name", os.path.splitext(os.path.basename(path))[0])
    check_name(study, path)
    for key in ("options", "sweeps", "solver_options", "solver_sweeps", "resolution_options",
                "solver_resolution_options"):
        study[key] = study.get(key) or {}
        if not isinstance(study[key], dict):
            sys.exit("study: %s: '%s' must be a mapping" % (path, key))
    for key, values in study["sweeps"].items():
        if not isinstance(values, list) or not values:
            sys.exit("study: %s: sweep '%s' must be a non-empty list" % (path, key))
    per_solver = study["solver_resolution_options"]
    for where, table in [("resolution_options", study["resolution_options"])] + [
            ("solver_resolution_options: %s" % k, v) for k, v in per_solver.items()]:
        if not isinstance(table, dict):
            sys.exit("study: %s: '%s' must be a mapping" % (path, where))
        for key, values in table.items():
            if not isinstance(values, list) or len(values) != len(study["resolutions"]):
                sys.exit("study: %s: %s '%s' needs one value per resolution (%d), got %s" % (
                    path, where, key, len(study["resolutions"]), values))
            table[key] = [values[i] for i in order]  # follow the resolutions into increasing nx
    # A metric given and missing from the runs is refused; the default one falls back to their first error.
    study["metric_given"] = "metric" in study
    try:
        study["metric_spec"] = parse_metric(study.get("metric", "l1_velocity"), path)
    except ValueError as e:
        sys.exit("study: %s" % e)
    study["metric"] = metric_label(study["metric_spec"])
    levels = study.get("levels")
    if levels is not None:
        def positive(v):  # YAML 1.1 reads 1e-3 (no dot) as a string
            try:
                return None if isinstance(v, bool) else float(v) if float(v) > 0 else None
            except (TypeError, ValueError):
                return None
        values = [positive(v) for v in levels] if isinstance(levels, list) else []
        if not values or None in values:
            sys.exit("study: %s: 'levels' must be a list of positive error levels, e.g. [1e-3, 3e-4]" % path)
        study["levels"] = sorted(values, reverse=True)
    return study


def is_scalar(v):
    return v is None or isinstance(v, (str, int, float, bool))


def check_types(study, path, solvers):
    """A key of the wrong type is refused in one line naming it and what it takes, before it fails
    deeper down as a Python error."""
    def refuse(key, want, example):
        sys.exit("study: %s: '%s' must be %s, got %r; e.g. %s" % (path, key, want, study.get(key), example))
    if not isinstance(study["case"], str) or not study["case"]:
        refuse("case", "a case name", "case: taylor_green")
    if not (isinstance(solvers, str) or (isinstance(solvers, list) and solvers and
                                         all(isinstance(x, str) for x in solvers))):
        sys.exit("study: %s: 'solvers' must be a solver name or a list of them, got %r; e.g. solvers: [isph, wcsph]"
                 % (path, solvers))
    n = study["resolutions"]
    if not isinstance(n, list) or not n or not all(
            not isinstance(x, bool) and (isinstance(x, int) or (isinstance(x, str) and x.isdigit())) and int(x) > 0
            for x in n):
        refuse("resolutions", "a list of positive integers (nx)", "resolutions: [16, 32, 64]")
    mpi = study.get("mpi")
    if mpi is not None and (isinstance(mpi, bool) or not isinstance(mpi, int) or mpi < 0):
        refuse("mpi", "a number of MPI ranks (0: no mpirun)", "mpi: 2")
    for key in ("solver_options", "solver_sweeps"):
        table = study.get(key) or {}
        if isinstance(table, dict):
            for solver, value in table.items():
                if value is not None and not isinstance(value, dict):
                    sys.exit("study: %s: '%s: %s' must be a mapping of options, got %r; e.g. %s: {%s: {cfl: %s}}"
                             % (path, key, solver, value, key, solver, "[0.1, 0.2]" if "sweeps" in key else "0.2"))
    options = study.get("options") or {}
    if isinstance(options, dict):
        for name, value in options.items():
            if not is_scalar(value):
                sys.exit("study: %s: option '%s' must be one value, got %r; a list of values is a sweep "
                         "(sweeps: {%s: [...]})" % (path, name, value, name))


def check_name(study, path):
    """The study's name names its folder (out/studies/<name>): one plain folder name, so that a study
    writes only under its own folder, never over another's results.csv or report.md."""
    name = study["name"]
    if not isinstance(name, str) or not name or name in (".", "..") or "/" in name or "\\" in name or "\0" in name:
        sys.exit("study: %s: 'name' must be a plain folder name (no '/', not '.' or '..'), got %r; "
                 "give e.g. name: %s" % (path, name, safe_name(os.path.splitext(os.path.basename(path))[0])))


def load_scene(study, path):
    """A study of a scene at several resolutions: 'scene:' gives scripts/make-scene's arguments (a list)
    or {command: [...]}, a program of one's own that writes the scene for '{nx}' into '{file}', run in the
    study file's folder. Each resolution then runs -case scene on its own file. A relative scene_file
    option is taken from the study file's folder too."""
    here = os.path.dirname(os.path.abspath(path))
    options = study.get("options")
    if isinstance(options, dict) and isinstance(options.get("scene_file"), str):
        options["scene_file"] = os.path.join(here, options["scene_file"])
    scene = study.get("scene")
    if scene is None:
        return
    if study.get("case", "scene") != "scene":
        sys.exit("study: %s: 'scene' runs -case scene; remove 'case: %s'" % (path, study["case"]))
    study["case"] = "scene"
    if isinstance(scene, list) and scene:
        study["scene"] = {"args": [str(a) for a in scene]}
    elif isinstance(scene, dict) and set(scene) == {"command"} and isinstance(scene["command"], list) and \
            scene["command"] and any("{file}" in str(a) for a in scene["command"]):
        study["scene"] = {"command": [str(a) for a in scene["command"]], "cwd": here}
    else:
        sys.exit("study: %s: 'scene' must be a non-empty list of scripts/make-scene arguments (without --nx and "
                 "-o), or {command: [...]} with '{nx}' and '{file}' where the scene's resolution and file go" % path)


def scene_for(scene, nx, out_dir):
    """The scene of one resolution: where its file goes and how it is made (execute.make_scene)."""
    if "args" in scene:
        name = safe_name("_".join(scene["args"]))
        file = os.path.join(out_dir, "scenes", "%s-nx%d.vtp" % (name, nx))
        return {"args": scene["args"] + ["--nx", str(nx)], "file": file}
    file = os.path.join(out_dir, "scenes", "scene-nx%d.vtp" % nx)
    return {"command": [a.replace("{nx}", str(nx)).replace("{file}", file) for a in scene["command"]],
            "cwd": scene["cwd"], "file": file}


def option_value(v):
    if v is None:
        return None
    if isinstance(v, bool):
        return "1" if v else "0"
    if isinstance(v, float):
        return repr(v)
    return str(v)


def option_args(options):
    args = []
    for k, v in options.items():
        k = str(k).lstrip("-")
        args.append("-" + k)
        v = option_value(v)
        if v is not None and v != "":
            args.append(v)
    return args


def sweep_choice(key, value):
    """(label value, options dict) of one sweep value: a scalar sets -key, a mapping sets several options."""
    if isinstance(value, dict):
        opts = {k: v for k, v in value.items() if k != "label"}
        label = value.get("label") or "+".join(option_value(v) or k for k, v in opts.items())
        return str(label), opts
    return option_value(value) if value is not None else "", {key: value}


def safe_name(s):
    return re.sub(r"[^A-Za-z0-9._=+-]", "_", s)


def resolution_options(study, solver, i):
    """The options refined with h at the i-th resolution: every solver's, then this solver's own."""
    options = {k: v[i] for k, v in study["resolution_options"].items()}
    options.update({k: v[i] for k, v in (study["solver_resolution_options"].get(solver) or {}).items()})
    return options


def plan_runs(study, out_dir, sph, mpi):
    """Every run of the study: dict(solver, nx, sweep {key: label}, args, dir, key, label)."""
    runs = []
    for solver in study["solvers"]:
        sweeps = dict(study["sweeps"])
        sweeps.update((study["solver_sweeps"].get(solver) or {}))
        keys = list(sweeps)
        choices = [[sweep_choice(k, v) for v in sweeps[k]] for k in keys]
        for combo in itertools.product(*choices) if keys else [()]:
            sweep = {k: c[0] for k, c in zip(keys, combo)}
            for i, nx in enumerate(study["resolutions"]):
                options = {"case": study["case"], "solver": solver, "nx": nx}
                scene = scene_for(study["scene"], nx, out_dir) if study.get("scene") else None
                if scene:  # the resolution is the scene file's: -case scene takes no -nx
                    del options["nx"]
                    options["scene_file"] = scene["file"]
                options.update(study["options"])
                options.update(study["solver_options"].get(solver) or {})
                options.update(resolution_options(study, solver, i))
                for _, opts in combo:
                    options.update(opts)
                options.setdefault("output_interval", 0)
                options["progress"] = 0
                name = "-".join([solver] + ["%s=%s" % (k, sweep[k]) for k in keys] + ["nx%d" % nx])
                run_dir = os.path.join(out_dir, safe_name(name))
                args = option_args(options) + ["-output_dir", run_dir]
                label = solver + "".join(", %s=%s" % (k, sweep[k]) for k in keys)
                runs.append({"solver": solver, "nx": nx, "sweep": sweep, "args": args, "dir": run_dir,
                             "label": label, "name": name, "scene": scene,
                             "command": (["mpirun", "-n", str(mpi), "--allow-run-as-root", "--oversubscribe"]
                                         if mpi and mpi > 0 else []) + [sph] + args,
                             "mpi": mpi or 0})
    return runs


def load_matrix(study, path):
    """Checks and normalises the 'matrix:' form of a study file."""
    known = {"name", "description", "matrix", "mpi"}
    unknown = sorted(set(study) - known)
    if unknown:
        sys.exit("study: %s: with 'matrix:', unknown key(s) %s (known: %s)" %
                 (path, ", ".join(unknown), ", ".join(sorted(known))))
    m = study["matrix"]
    if not isinstance(m, dict):
        sys.exit("study: %s: 'matrix' must be a mapping with 'rows' and 'columns'" % path)
    unknown = sorted(set(m) - {"rows", "columns", "options", "metric"})
    if unknown:
        sys.exit("study: %s: matrix: unknown key(s) %s (known: columns, metric, options, rows)" % (path, ", ".join(unknown)))
    m["options"] = m.get("options") or {}
    if not isinstance(m["options"], dict):
        sys.exit("study: %s: matrix: 'options' must be a mapping of options, got %r" % (path, m["options"]))
    for what, need, allowed in (("rows", "case", {"label", "case", "scene", "options", "solver_options", "metric"}),
                                ("columns", "solver", {"label", "solver", "options"})):
        items = m.get(what)
        if not isinstance(items, list) or not items:
            sys.exit("study: %s: matrix: '%s' must be a non-empty list" % (path, what))
        labels = set()
        for i, it in enumerate(items):
            # A row with 'scene:' (scripts/make-scene's arguments) runs -case scene on the file it makes.
            if isinstance(it, dict) and what == "rows" and "scene" in it:
                if not isinstance(it["scene"], list) or not it["scene"] or it.get("case", "scene") != "scene":
                    sys.exit("study: %s: matrix: rows[%d]: 'scene' must be a non-empty list of scripts/make-scene "
                             "arguments, without 'case' (or with case: scene)" % (path, i))
                it["scene"] = [str(a) for a in it["scene"]]
                it["case"] = "scene"
            if not isinstance(it, dict) or need not in it:
                sys.exit("study: %s: matrix: %s[%d] must be a mapping with '%s'" % (path, what, i, need))
            bad = sorted(set(it) - allowed)
            if bad:
                sys.exit("study: %s: matrix: %s[%d]: unknown key(s) %s (known: %s)" %
                         (path, what, i, ", ".join(bad), ", ".join(sorted(allowed))))
            it["label"] = str(it.get("label") or it[need])
            if it["label"] in labels:
                sys.exit("study: %s: matrix: two %s labelled '%s'" % (path, what, it["label"]))
            labels.add(it["label"])
            for key in ("options", "solver_options"):
                it[key] = it.get(key) or {}
                if not isinstance(it[key], dict):
                    sys.exit("study: %s: matrix: %s '%s': '%s' must be a mapping" % (path, what, it["label"], key))
            it.setdefault("metric", m.get("metric"))
    study.setdefault("name", os.path.splitext(os.path.basename(path))[0])
    check_name(study, path)
    return study


def plan_matrix_runs(study, out_dir, sph, mpi):
    """One run per (row, column): options = matrix options, then the row's, the column's, and the row's
    solver_options for the column's solver (or keyed by the column's label)."""
    m = study["matrix"]
    runs = []
    for i, row in enumerate(m["rows"]):
        for j, col in enumerate(m["columns"]):
            options = {"case": row["case"], "solver": col["solver"]}
            options.update(m["options"])
            options.update(row["options"])
            options.update(col["options"])
            options.update(row["solver_options"].get(col["solver"]) or {})
            options.update(row["solver_options"].get(col["label"]) or {})
            options.setdefault("output_interval", 0)
            options.setdefault("checkpoint_interval", 0)
            options["progress"] = 0
            name = "r%d-%s--c%d-%s" % (i + 1, row["label"], j + 1, col["label"])
            run_dir = os.path.join(out_dir, safe_name(name))
            scene = None
            if row.get("scene"):  # made when the run starts (execute.py), once for the row's columns
                # Named by its arguments: other arguments, another file, and the runs are not up to date.
                file = safe_name("_".join(row["scene"])) + ".vtp"
                scene = {"args": row["scene"], "file": os.path.join(out_dir, "scenes", file)}
                options["scene_file"] = scene["file"]
            args = option_args(options) + ["-output_dir", run_dir]
            try:
                nx = int(options.get("nx") or 0)
            except (TypeError, ValueError):
                nx = 0
            runs.append({"solver": col["solver"], "nx": nx, "sweep": {}, "args": args, "dir": run_dir,
                         "label": "%s | %s" % (row["label"], col["label"]), "name": name,
                         "row": row["label"], "column": col["label"], "metric": row["metric"], "scene": scene,
                         "command": (["mpirun", "-n", str(mpi), "--allow-run-as-root", "--oversubscribe"]
                                     if mpi and mpi > 0 else []) + [sph] + args,
                         "mpi": mpi or 0})
    return runs
