# Shared by the CLI tests (sourced; expects $sph, $tmp and $fail to be set by the caller).
# expect_error <pattern> <args...>: a non-zero exit and exactly one line on stderr matching pattern
# (warnings, "sph: warning: ...", may precede it).
expect_error() {
  local pattern="$1"; shift
  "$sph" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  local lines; lines=$(grep -v '^sph: warning:' "$tmp/stderr" | grep -c .)
  if [ $rc -eq 0 ] || [ "$lines" -ne 1 ] || ! grep -qE -- "$pattern" "$tmp/stderr"; then
    echo "FAIL: sph $* -> rc=$rc, stderr:"; cat "$tmp/stderr"; fail=1
  else
    echo "ok: sph $* -> $(cat "$tmp/stderr")"
  fi
}
# expect_ok <args...>: exit 0.
expect_ok() {
  if "$sph" "$@" >"$tmp/stdout" 2>"$tmp/stderr"; then echo "ok: sph $*"
  else echo "FAIL: sph $* -> exit non-zero:"; cat "$tmp/stderr"; fail=1; fi
}
# expect_json <file> <python expression on s, the parsed file> <description>
expect_json() {
  if python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); sys.exit(0 if eval(sys.argv[2]) else 1)' "$1" "$2" 2>/dev/null
  then echo "ok: $3"; else echo "FAIL: $3 ($2 on $1)"; fail=1; fi
}
