#!/usr/bin/env bash
# Command-line behaviour: bad input gives one line naming the cause and a non-zero exit; -help lists
# the options with their defaults.   usage: options.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
# expect_error <pattern> <args...>: exit code non-zero, exactly one line on stderr matching pattern
expect_error() {
  local pattern="$1"; shift
  "$sph" "$@" -output_dir "$tmp/out" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  local lines; lines=$(grep -c . "$tmp/stderr")
  if [ $rc -eq 0 ] || [ "$lines" -ne 1 ] || ! grep -qE -- "$pattern" "$tmp/stderr"; then
    echo "FAIL: sph $* -> rc=$rc, stderr:"; cat "$tmp/stderr"; fail=1
  else
    echo "ok: sph $* -> $(cat "$tmp/stderr")"
  fi
}
small="-case taylor_green -nx 8 -t_end 0.01 -progress 0"
expect_error "unknown option -foo" $small -foo 1
expect_error "did you mean -shifting" $small -shiftng 0
expect_error "unknown option -ksp_typo" $small -ksp_typo cg
expect_error "did you mean -ksp_type" $small -ksp_tpye cg
expect_error "did you mean -c0" -case taylor_green -solver wcsph -nx 8 -c00 3
expect_error "-nx must be" $small -nx -3
expect_error "-re must be positive" $small -re 0
expect_error "unknown case|Unknown|case" -case no_such_case
expect_error "-cfl must be" $small -cfl 5
expect_error "kernel" $small -kernel no_such_kernel
expect_error "options|file|PETSc" -options_file "$tmp/missing.opts"
expect_error "use -solver compressible" -case sod -solver wcsph -nx 48 -progress 0
expect_error "use -solver compressible" -case toy_star -solver isph -nx 50 -progress 0

# -help: exit 0, documents case, solver, driver and PETSc KSP options with defaults.
"$sph" -help >"$tmp/help" 2>&1 || { echo "FAIL: -help exited non-zero"; fail=1; }
for opt in -case -solver -nx -re -t_end -cfl -shifting -kernel -output_dir -ksp_type -pc_type; do
  grep -q -- "$opt" "$tmp/help" || { echo "FAIL: -help does not list $opt"; fail=1; }
done

# A case file loads and the command line overrides it.
"$sph" -options_file "$src/cases/taylor_green.opts" -nx 8 -t_end 0.01 -progress 0 -output_dir "$tmp/tg" \
  >/dev/null 2>"$tmp/stderr" || { echo "FAIL: case file run"; cat "$tmp/stderr"; fail=1; }
grep -q '"nx": 8' "$tmp/tg/summary.json" || { echo "FAIL: -nx did not override the case file"; fail=1; }
exit $fail
