#!/usr/bin/env bash
# scripts/study: a tiny convergence study (Taylor-Green, nx 8 and 12, both solvers, one ISPH sweep value
# the program rejects) gives results.csv, report.md and plots; a rerun skips every run; the failed run
# is recorded without stopping the study; the order / Pareto arithmetic passes its self-test.
#   usage: study.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
study="$src/scripts/study"
say() { echo "$@"; }
bad() { echo "FAIL: $*"; fail=1; }

/usr/bin/python3 -c 'import matplotlib, yaml' 2>/dev/null ||
  { bad "/usr/bin/python3 lacks matplotlib or PyYAML (scripts/install-deps installs python3-matplotlib python3-yaml)"; exit 1; }

# Order and Pareto functions on synthetic data (e.g. 4e-2 -> 1e-2 at h 0.1 -> 0.05 is order 2).
"$study" --self-test >"$tmp/selftest" 2>&1 || { bad "--self-test"; cat "$tmp/selftest"; }
grep -q "order 4e-2 -> 1e-2 at h 0.1 -> 0.05 is 2" "$tmp/selftest" && say "ok: --self-test ($(tail -1 "$tmp/selftest"))"

# First run: every run is made, two of them fail (-cfl 5) without stopping the study.
"$study" "$src/cases/studies/tiny_test.yaml" --sph "$sph" --out "$tmp/s" >"$tmp/run1" 2>&1 ||
  { bad "study exited non-zero"; cat "$tmp/run1"; }
grep -q "ran 6 runs (2 failed), skipped 0 runs" "$tmp/run1" && say "ok: first run: $(grep '^ran ' "$tmp/run1")" ||
  { bad "first run did not make 6 runs with 2 failures"; cat "$tmp/run1"; }
for f in results.csv report.md error_vs_h.png errors_vs_h.png pareto.png ksp_iterations.png; do
  [ -s "$tmp/s/$f" ] && say "ok: $f written" || bad "$f missing or empty"
done
n_done=$(grep -c ',completed,' "$tmp/s/results.csv")
n_fail=$(grep -c ',failed,"-cfl must be in' "$tmp/s/results.csv")
[ "$n_done" -eq 4 ] && [ "$n_fail" -eq 2 ] && say "ok: results.csv has 4 completed rows and 2 failed with the reason" ||
  { bad "results.csv: $n_done completed, $n_fail failed with the -cfl message"; cat "$tmp/s/results.csv"; }
head -1 "$tmp/s/results.csv" | grep -q "^cfl,solver,nx,N,h,steps,wall_time_s,time_per_particle_step_s,ksp_iterations_mean,ksp_iterations_max,status,failure,.*l1_velocity" &&
  say "ok: results.csv columns" || { bad "results.csv header"; head -1 "$tmp/s/results.csv"; }
# ISPH rows carry KSP iterations, WCSPH rows leave them empty.
grep -qE '^0\.2,isph,8,64,[^,]+,[0-9]+,[^,]+,[^,]+,[0-9.]+,[0-9]+,completed' "$tmp/s/results.csv" &&
  grep -qE '^,wcsph,8,64,[^,]+,[0-9]+,[^,]+,[^,]+,,,completed' "$tmp/s/results.csv" &&
  say "ok: KSP iterations for ISPH only" || { bad "KSP columns"; cat "$tmp/s/results.csv"; }
for want in "## Observed orders" "### isph, cfl=0.2" "### wcsph" "## Failed runs" "## Speed against accuracy" \
            "](pareto.png)" "](error_vs_h.png)" "](ksp_iterations.png)"; do
  grep -qF -- "$want" "$tmp/s/report.md" || bad "report.md lacks '$want'"
done
[ -s "$tmp/s/isph-cfl=0.2-nx8/run.json" ] && [ -s "$tmp/s/wcsph-nx12/summary.json" ] && say "ok: run folders" ||
  bad "run folders"

# Second run: everything is up to date.
"$study" "$src/cases/studies/tiny_test.yaml" --sph "$sph" --out "$tmp/s" >"$tmp/run2" 2>&1 || bad "rerun exited non-zero"
grep -q "ran 0 runs (0 failed), skipped 6 runs" "$tmp/run2" && say "ok: rerun: $(grep '^ran ' "$tmp/run2")" ||
  { bad "rerun did not skip all runs"; cat "$tmp/run2"; }

# A new resolution runs only the 3 new runs (one per line), the others stay up to date.
sed 's/resolutions: \[8, 12\]/resolutions: [8, 12, 10]/' "$src/cases/studies/tiny_test.yaml" >"$tmp/tiny3.yaml"
"$study" "$tmp/tiny3.yaml" --sph "$sph" --out "$tmp/s" >"$tmp/run3" 2>&1 || bad "third run exited non-zero"
grep -q "ran 3 runs (1 failed), skipped 6 runs" "$tmp/run3" && say "ok: added resolution: $(grep '^ran ' "$tmp/run3")" ||
  { bad "adding a resolution did not run exactly the 3 new runs"; cat "$tmp/run3"; }

# Options refined with h: one value per resolution, in the order the resolutions are listed; the sound
# speed each run used (summary.json) follows its own resolution.
cat >"$tmp/refined.yaml" <<'YAML'
name: tiny_refined
case: taylor_green
solvers: [wcsph]
resolutions: [12, 8]
options: {re: 100, t_end: 0.02}
solver_resolution_options:
  wcsph: {c0_factor: [20, 10]}
levels: [0.5, 1e-9]
YAML
"$study" "$tmp/refined.yaml" --sph "$sph" --out "$tmp/r" >"$tmp/run4" 2>&1 || { bad "refined study exited non-zero"; cat "$tmp/run4"; }
c0_of() { /usr/bin/python3 -c 'import json,sys; print("%g" % json.load(open(sys.argv[1]))["models"]["equation_of_state"]["c0"])' "$1"; }
c8=$(c0_of "$tmp/r/wcsph-nx8/summary.json"); c12=$(c0_of "$tmp/r/wcsph-nx12/summary.json")
[ "$c8" = 10 ] && [ "$c12" = 20 ] && say "ok: resolution options follow their resolution (c0 $c8 at nx 8, $c12 at nx 12)" ||
  bad "resolution options: c0 $c8 at nx 8 (want 10), $c12 at nx 12 (want 20)"
grep -qF -- '`-c0_factor` 10, 20 at nx = 8, 12' "$tmp/r/report.md" && say "ok: report names the refined options" ||
  bad "report.md does not name the options refined with h"
# The speed table has the study's own error levels: 0.5 reached by the coarsest run, 1e-9 by none.
grep -qE '^\| 0\.5 \| ≤ ' "$tmp/r/report.md" && grep -qE '^\| 1e-09 \| – ' "$tmp/r/report.md" &&
  say "ok: speed table at the study's levels" || { bad "speed table levels"; sed -n '/Speed against/,/In words/p' "$tmp/r/report.md"; }
# --nx takes any resolutions, except where options follow the study's own.
"$study" "$src/cases/studies/tiny_test.yaml" --sph "$sph" --out "$tmp/s" --nx 9 --dry-run >"$tmp/run6" 2>&1 &&
  grep -q -- "-nx 9 " "$tmp/run6" && say "ok: --nx 9, not in the study file, is planned" || { bad "--nx 9"; cat "$tmp/run6"; }
"$study" "$tmp/refined.yaml" --sph "$sph" --out "$tmp/r" --nx 12 --dry-run >"$tmp/run7" 2>&1 &&
  grep -q -- "-c0_factor 20 " "$tmp/run7" && ! grep -q -- "-nx 8 " "$tmp/run7" &&
  say "ok: --nx 12 keeps nx 12's resolution options" || { bad "--nx 12 with resolution options"; cat "$tmp/run7"; }
if "$study" "$tmp/refined.yaml" --sph "$sph" --out "$tmp/r" --nx 9 --dry-run >"$tmp/run8" 2>&1; then
  bad "--nx 9 accepted although the study's options follow its resolutions"
else
  grep -q "which its resolution options follow" "$tmp/run8" && say "ok: --nx 9 refused with resolution options" ||
    { bad "--nx refusal message"; cat "$tmp/run8"; }
fi
sed 's/c0_factor: \[20, 10\]/c0_factor: [20]/' "$tmp/refined.yaml" >"$tmp/refined_bad.yaml"
if "$study" "$tmp/refined_bad.yaml" --sph "$sph" --out "$tmp/r2" >"$tmp/run5" 2>&1; then
  bad "a resolution option with too few values was accepted"
else
  grep -q "needs one value per resolution (2)" "$tmp/run5" && say "ok: too few resolution values refused: $(tail -1 "$tmp/run5")" ||
    { bad "refusal message"; cat "$tmp/run5"; }
fi
exit $fail
