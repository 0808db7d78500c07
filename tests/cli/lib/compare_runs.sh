# Shared by the CLI tests that run the same case two ways and compare the summaries (sourced; expects
# $sph, $tmp, $mpiexec and $fail to be set by the caller).
# run <label> <ranks> <args...>
run() {
  local label="$1" n="$2"; shift 2
  if ! "$mpiexec" -n "$n" "$sph" "$@" -output_dir "$tmp/$label" -progress 0 -output_interval 0 >"$tmp/$label.log" 2>&1; then
    echo "FAIL: $label ($n ranks) exited non-zero:"; tail -5 "$tmp/$label.log"; fail=1
  fi
}
# compare <label a> <label b> <relative tolerance on every error norm> [N: KSP iterations per step may differ
# by N (default 1: one solve per step, within one iteration); any: by any number]
compare() {
  python3 - "$tmp/$1/summary.json" "$tmp/$2/summary.json" "$3" "${4:-}" <<'PY' || fail=1
import csv, json, math, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
ksp_a, ksp_b = ([float(r["ksp_iterations"]) for r in csv.DictReader(open(p.replace("summary.json", "timeseries.csv")))]
                for p in sys.argv[1:3])
tol = float(sys.argv[3])
ok = a["status"] == b["status"] == "completed" and a["steps"] == b["steps"]
worst = 0.0
for k, va in a["errors"].items():
    vb = b["errors"][k]
    if va is None and vb is None: continue  # NaN (e.g. a plateau not formed yet) in both
    rel = abs(va - vb) / max(abs(va), 1e-300)
    worst = max(worst, rel)
    ok &= rel <= tol
# Per step (a resumed run's series holds only the steps after the restart).
ksp_a = ksp_a[len(ksp_a) - len(ksp_b):]
if sys.argv[4] != "any": ok &= all(abs(x - y) <= int(sys.argv[4] or 1) for x, y in zip(ksp_a, ksp_b))
print(("ok" if ok else "FAIL") + f": {sys.argv[1].split('/')[-2]} vs {sys.argv[2].split('/')[-2]}: "
      f"largest relative difference of the error norms {worst:.2e} (tolerance {tol:g}), ranks {a['mpi_ranks']} / {b['mpi_ranks']}, "
      f"threads per rank {a.get('threads_per_rank')} / {b.get('threads_per_rank')}")
sys.exit(0 if ok else 1)
PY
}

