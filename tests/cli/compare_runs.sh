#!/usr/bin/env bash
# scripts/compare-runs: a run against itself differs by exactly 0; Taylor-Green nx 24, ISPH against WCSPH at
# t = 0.1, differs by less than 5% in velocity (L1), and by no more than the two runs' own errors against
# the analytic field allow (|u_A - u_B| <= |u_A - u_exact| + |u_B - u_exact|: a biased interpolation, e.g.
# a plain Shepard sum at 2.6e-2, fails this); the same ISPH run on 2 ranks (.pvtp frames) matches the
# 1-rank run particle by particle; a missing run directory, .pvd or frame list gives one error line, exit 1.
#   usage: compare_runs.sh <sph executable> <source dir>; $MPIEXEC names mpiexec.
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mpiexec="${MPIEXEC:-mpiexec}"
fail=0
cr="$src/scripts/compare-runs"
say() { echo "$@"; }
bad() { echo "FAIL: $*"; fail=1; }

/usr/bin/python3 -c 'import numpy, matplotlib' 2>/dev/null ||
  { bad "/usr/bin/python3 lacks numpy or matplotlib (scripts/install-deps installs python3-matplotlib)"; exit 1; }

# run <label> <ranks> <args...>
run() {
  local label="$1" n="$2"; shift 2
  local launch=("$sph"); [ "$n" -gt 1 ] && launch=("$mpiexec" -n "$n" "$sph")
  "${launch[@]}" "$@" -threads 1 -progress 0 -output_interval 0 -output_dir "$tmp/$label" >"$tmp/$label.log" 2>&1 ||
    { bad "sph run $label ($n ranks) exited non-zero"; tail -5 "$tmp/$label.log"; return 1; }
}
# field <json file> <key>: a number from compare-runs --json (or a summary.json path such as errors.l1_velocity)
field() {
  /usr/bin/python3 -c 'import functools, json, sys
print(functools.reduce(lambda d, k: d[k], sys.argv[2].split("."), json.load(open(sys.argv[1]))))' "$1" "$2"
}
# check <description> <python expression> <name=value...>: the expression over those numbers holds
check() {
  local what="$1" expr="$2"; shift 2
  if /usr/bin/python3 -c 'import sys
v = {k: float(x) for k, x in (a.split("=", 1) for a in sys.argv[2:])}
sys.exit(0 if eval(sys.argv[1], {}, v) else 1)' "$expr" "$@"; then
    say "ok: $what ($*)"
  else
    bad "$what: $expr is false for $*"
  fi
}

tgv="-case taylor_green -nx 24 -t_end 0.1"
run isph 1 $tgv -solver isph -ppe_ksp_rtol 1e-10 && run wcsph 1 $tgv -solver wcsph || exit 1

# A run against itself: particle by particle, exactly zero.
"$cr" "$tmp/isph" "$tmp/isph" --json "$tmp/self.json" >"$tmp/self.out" 2>&1 ||
  { bad "self comparison exited non-zero"; cat "$tmp/self.out"; }
grep -q "particle by particle" "$tmp/self.out" || bad "self comparison did not match particles by id"
check "run against itself" "l1u == 0 and linfu == 0 and l1p == 0 and linfp == 0" \
  l1u="$(field "$tmp/self.json" l1_velocity)" linfu="$(field "$tmp/self.json" linf_velocity)" \
  l1p="$(field "$tmp/self.json" l1_pressure)" linfp="$(field "$tmp/self.json" linf_pressure)"

# ISPH against WCSPH: interpolated (the particles differ), close, and within the sum of their own errors.
"$cr" "$tmp/isph" "$tmp/wcsph" --periodic x,y --json "$tmp/iw.json" -o "$tmp/iw.png" >"$tmp/iw.out" 2>&1 ||
  { bad "ISPH vs WCSPH exited non-zero"; cat "$tmp/iw.out"; }
cat "$tmp/iw.out"
grep -q "B interpolated onto A" "$tmp/iw.out" && grep -q "frames used: A at t = 0.1, B at t = 0.1" "$tmp/iw.out" ||
  bad "ISPH vs WCSPH: expected an interpolation at t = 0.1"
check "ISPH vs WCSPH velocity L1 below 5%" "l1 < 0.05" l1="$(field "$tmp/iw.json" l1_velocity)"
# summary.json's l1_velocity is normalised by the analytic amplitude, compare-runs' by max|u_A|.
check "ISPH vs WCSPH velocity L1 within the runs' errors against the analytic field" \
  "l1 * umax / amp <= 1.5 * (ea + eb)" \
  l1="$(field "$tmp/iw.json" l1_velocity)" umax="$(field "$tmp/iw.json" velocity_scale)" \
  amp="$(/usr/bin/python3 -c 'import math, sys; print(math.exp(-8 * math.pi**2 * float(sys.argv[1]) * 0.1))' \
         "$(field "$tmp/isph/summary.json" physics.nu)")" \
  ea="$(field "$tmp/isph/summary.json" errors.l1_velocity)" eb="$(field "$tmp/wcsph/summary.json" errors.l1_velocity)"
head -c 8 "$tmp/iw.png" | grep -q PNG && say "ok: -o wrote a PNG" || bad "-o did not write a PNG"

# 1 rank against 2 ranks (.pvtp + pieces): the same particles, the same values to the solver tolerance.
if run isph2 2 $tgv -solver isph -ppe_ksp_rtol 1e-10; then
  "$cr" "$tmp/isph" "$tmp/isph2" --periodic x,y --json "$tmp/mpi.json" >"$tmp/mpi.out" 2>&1 ||
    { bad "1 vs 2 ranks exited non-zero"; cat "$tmp/mpi.out"; }
  grep -q "frame particles_00001.pvtp" "$tmp/mpi.out" && grep -q "particle by particle" "$tmp/mpi.out" ||
    { bad "1 vs 2 ranks: expected .pvtp frames compared particle by particle"; cat "$tmp/mpi.out"; }
  check "1 vs 2 ranks" "l1u < 1e-6 and l1p < 1e-6 and n == 576" l1u="$(field "$tmp/mpi.json" l1_velocity)" \
    l1p="$(field "$tmp/mpi.json" l1_pressure)" n="$(field "$tmp/mpi.json" n_compared)"
fi

# expect_error <pattern> <args...>: exit 1, exactly one line on stderr matching pattern
expect_error() {
  local pattern="$1"; shift
  "$cr" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  if [ $rc -ne 1 ] || [ "$(grep -c . "$tmp/stderr")" -ne 1 ] || ! grep -qE -- "$pattern" "$tmp/stderr"; then
    bad "compare-runs $* -> rc=$rc, stderr: $(cat "$tmp/stderr")"
  else
    say "ok: compare-runs $* -> $(cat "$tmp/stderr")"
  fi
}
mkdir -p "$tmp/empty" "$tmp/noframes"
printf '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n  <Collection>\n  </Collection>\n</VTKFile>\n' \
  >"$tmp/noframes/particles.pvd"
expect_error "^compare-runs: error: run directory .*/missing does not exist$" "$tmp/missing" "$tmp/isph"
expect_error "^compare-runs: error: .*/empty has no particles.pvd" "$tmp/isph" "$tmp/empty"
expect_error "^compare-runs: error: .*/noframes/particles.pvd lists no frames$" "$tmp/noframes" "$tmp/isph"
exit $fail
