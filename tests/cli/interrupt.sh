#!/usr/bin/env bash
# SIGINT, SIGTERM and SIGHUP (a closed terminal) end a run cleanly: exit 130 / 143 / 129, status
# "interrupted" in summary.json, a frame of the state reached and a checkpoint from which -restart
# completes the run as if uninterrupted. Output to a closed pipe does not end a run (SIGPIPE ignored;
# before, PETSc's crash handler took it: exit 59, no summary.json).
#   usage: interrupt.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
run="-case poiseuille -solver isph -nx 20 -t_end 1 -progress 0 -output_interval 0 -checkpoint_interval 0 -ppe_ksp_rtol 1e-12"
# interrupt <signal> <dir>: starts a long run, signals it after a few steps, checks what it left.
interrupt() {
  local sig="$1" d="$2" want="$3"
  "$sph" $run -output_dir "$d" >"$tmp/out" 2>"$tmp/err" &
  local pid=$!
  for _ in $(seq 300); do [ -f "$d/timeseries.csv" ] && [ "$(wc -l <"$d/timeseries.csv")" -ge 4 ] && break; sleep 0.05; done
  kill "-$sig" $pid; wait $pid; local rc=$?
  [ $rc -eq "$want" ] && echo "ok: $sig -> exit $rc" || { echo "FAIL: $sig -> exit $rc (want $want)"; cat "$tmp/err"; fail=1; }
  grep -q "interrupted by SIG$sig" "$tmp/err" || { echo "FAIL: no message"; cat "$tmp/err"; fail=1; }
  expect_json "$d/summary.json" "s['status'] == 'interrupted' and s['signal'] == 'SIG$sig' and s['steps'] > 0" "$sig: summary says interrupted"
  [ -f "$d/checkpoint.bin" ] && [ ! -e "$d/checkpoint.bin.tmp" ] || { echo "FAIL: $sig: no checkpoint"; fail=1; }
  python3 - "$d" <<'PY' || fail=1
import json, re, sys
d = sys.argv[1]; s = json.load(open(d + "/summary.json"))
last = float(re.findall(r'timestep="([^"]+)"', open(d + "/particles.pvd").read())[-1])
ok = abs(last - s["t_final"]) <= 1e-12 * max(1, s["t_final"])
print(("ok" if ok else "FAIL") + f": last frame at t = {last}, summary t_final = {s['t_final']}")
sys.exit(0 if ok else 1)
PY
}
interrupt TERM "$tmp/term" 143
interrupt INT "$tmp/int" 130
interrupt HUP "$tmp/hup" 129

# A reader that stops reading: the run goes on to its end.
"$sph" -case taylor_green -nx 48 -t_end 1 -threads 1 -output_dir "$tmp/pipe" 2>&1 | head -c 10 >/dev/null
rc=${PIPESTATUS[0]}
[ "$rc" -eq 0 ] && echo "ok: output to a closed pipe -> exit 0" || { echo "FAIL: output to a closed pipe -> exit $rc (want 0)"; fail=1; }
expect_json "$tmp/pipe/summary.json" "s['status'] == 'completed'" "closed pipe: the run completed"

# Resume and compare with the run that was never interrupted: a checkpoint changes nothing in a run,
# and a restart on as many ranks puts the particles and their lists back as they were, so the time
# series (each step's iterations included), the errors and the iteration statistics are the same, byte
# for byte.
expect_ok $run -output_dir "$tmp/whole"
expect_ok $run -output_dir "$tmp/int" -restart "$tmp/int/checkpoint.bin"
python3 - "$tmp/whole" "$tmp/int" <<'PY' || fail=1
import json, sys
a, b = (json.load(open(d + "/summary.json")) for d in sys.argv[1:])
rows = [open(d + "/timeseries.csv").read() for d in sys.argv[1:]]
ok = rows[0] == rows[1] and a["errors"] == b["errors"] and a["ksp"] == b["ksp"]
ok &= a["steps"] == b["steps"] and len(b["history"]) == 2 and b["history"][0]["status"].startswith("interrupted")
print(("ok" if ok else "FAIL") + f": resumed after step {b['history'][0]['steps'][1]} of {a['steps']}: time series, errors"
      f" and iteration statistics {'as' if ok else 'differ from'} uninterrupted")
sys.exit(0 if ok else 1)
PY
exit $fail
