#!/usr/bin/env bash
# scripts/study, matrix form: a tiny stability matrix (2 cases x 3 solvers, very short runs) gives
# matrix.csv and matrix.md; the gas case with ISPH is "n/a" with the program's refusal as the reason (not
# "failed"); Taylor-Green with ISPH is ok with a number; a row's solver_options reach only that solver;
# a rerun skips every cell.
#   usage: study_matrix.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
study="$src/scripts/study"
say() { echo "$@"; }
bad() { echo "FAIL: $*"; fail=1; }

/usr/bin/python3 -c 'import yaml' 2>/dev/null ||
  { bad "/usr/bin/python3 lacks PyYAML (scripts/install-deps installs python3-yaml)"; exit 1; }

cat >"$tmp/tiny_matrix.yaml" <<'YAML'
name: tiny_matrix
matrix:
  rows:
    - {label: "TGV", case: taylor_green, options: {nx: 8, t_end: 0.02}, metric: l1_velocity}
    - label: "Sod"
      case: sod
      options: {nx: 48, t_end: 0.01}
      solver_options: {compressible: {kernel: cubic_spline, conductivity: 1}}   # compressible only
      metric: l1_density
  columns:
    - {label: "ISPH", solver: isph}
    - {label: "WCSPH", solver: wcsph}
    - {label: "compressible", solver: compressible}
YAML

"$study" "$tmp/tiny_matrix.yaml" --sph "$sph" --out "$tmp/m" >"$tmp/run1" 2>&1 ||
  { bad "study exited non-zero"; cat "$tmp/run1"; }
grep -q "^ran 6 runs (.* failed), skipped 0 runs" "$tmp/run1" && say "ok: first run: $(grep '^ran ' "$tmp/run1")" ||
  { bad "first run did not make 6 runs"; cat "$tmp/run1"; }
for f in matrix.csv matrix.md; do
  [ -s "$tmp/m/$f" ] && say "ok: $f written" || bad "$f missing or empty"
done
csv="$tmp/m/matrix.csv"
head -1 "$csv" | grep -q "^row,column,status,reason,metric,value,wall_time_s,steps" && say "ok: matrix.csv columns" ||
  { bad "matrix.csv header"; head -1 "$csv"; }
grep -qE '^Sod,ISPH,n/a,.*use -solver compressible' "$csv" && say "ok: Sod x ISPH is n/a with the refusal" ||
  { bad "Sod x ISPH is not n/a with the refusal reason"; cat "$csv"; }
grep -qE '^Sod,WCSPH,n/a,' "$csv" && say "ok: Sod x WCSPH is n/a (the row's compressible options did not reach it)" ||
  { bad "Sod x WCSPH is not n/a"; cat "$csv"; }
grep -qE '^TGV,ISPH,ok,,l1_velocity,[0-9.]+(e-?[0-9]+)?,[0-9.]+,[0-9]+,' "$csv" && say "ok: TGV x ISPH is ok with a number" ||
  { bad "TGV x ISPH is not ok with a numeric l1_velocity"; cat "$csv"; }
grep -qE '^Sod,compressible,ok,,l1_density,[0-9.]+' "$csv" && say "ok: Sod x compressible is ok" ||
  { bad "Sod x compressible is not ok"; cat "$csv"; }
grep -q -- "-kernel cubic_spline" "$tmp"/m/*Sod*compressible/run.json && ! grep -q -- "conductivity" "$tmp"/m/*Sod*ISPH/run.json &&
  say "ok: row solver_options for the compressible column only" || bad "row solver_options not applied per solver"
md="$tmp/m/matrix.md"
grep -qF "| case | ISPH | WCSPH | compressible |" "$md" && grep -qE '^\| TGV \| ok, l1_velocity=' "$md" &&
  grep -qE '^\| Sod \| n/a \(' "$md" && grep -qF -- "- **TGV**" "$md" && say "ok: matrix.md table and per-case sentences" ||
  { bad "matrix.md content"; cat "$md"; }

"$study" "$tmp/tiny_matrix.yaml" --sph "$sph" --out "$tmp/m" >"$tmp/run2" 2>&1 || bad "rerun exited non-zero"
grep -q "ran 0 runs (0 failed), skipped 6 runs" "$tmp/run2" && say "ok: rerun: $(grep '^ran ' "$tmp/run2")" ||
  { bad "rerun did not skip every cell"; cat "$tmp/run2"; }
exit $fail
