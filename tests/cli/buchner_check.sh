#!/usr/bin/env bash
# cases/scenes/dam_break_buchner.yaml and scripts/buchner-check. The scene starts and writes its two
# probes' columns; the check, given the experiment's own curve as a run (in uneven steps, in SI units
# with H = 0.6), finds the experiment's figures and the experiment's own RMS floor (its averaging).
#   usage: buchner_check.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
"$sph" -case scene -scene_file "$src/cases/scenes/dam_break_buchner.yaml" -nx 20 -max_steps 2 -progress 0 \
  -output_dir "$tmp/start" >/dev/null 2>&1 || { echo "FAIL: the scene did not run two steps"; fail=1; }
head -1 "$tmp/start/timeseries.csv" | grep -q "probe_P1_p,probe_P1_low_p" \
  || { echo "FAIL: no probe columns in timeseries.csv"; fail=1; }
mkdir -p "$tmp/run"
/usr/bin/python3 - "$tmp/run" "$src/cases/dam_break/data/buchner_2002_p1.csv" <<'PY'
import csv, json, math, sys
run, data = sys.argv[1], sys.argv[2]
curve = [(float(r["T"]), float(r["P"])) for r in csv.DictReader(l for l in open(data) if not l.startswith("#"))]
H, g, rho = 0.6, 9.81, 1000.0
st, sp = math.sqrt(H / g), rho * g * H
def P(T):
    for (t0, p0), (t1, p1) in zip(curve, curve[1:]):
        if t0 <= T <= t1:
            return p0 + (p1 - p0) * (T - t0) / (t1 - t0) if t1 > t0 else p0
    return 0.0
with open(f"{run}/timeseries.csv", "w") as f:
    f.write("step,t,dt,probe_P1_p\n")
    T, k = 0.0, 0
    while T < 7.25:
        dT = 0.002 if k % 2 else 0.003
        T += dT; k += 1
        f.write(f"{k},{T * st!r},{dT * st!r},{P(T - dT / 2) * sp!r}\n")
json.dump({"parameters": {"gravity": [0, -g], "rho0": rho}}, open(f"{run}/summary.json", "w"))
PY
out=$("$src/scripts/buchner-check" "$tmp/run") || { echo "FAIL: buchner-check exited non-zero"; exit 1; }
echo "$out"
PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$out" <<'PY'
import sys
from checks import check, finish
lines = sys.argv[1].splitlines()
exp, run = [float(x) for x in lines[1].split()[1:6]], [float(x) for x in lines[2].split()[1:6]]
for name, e, r in zip(["arrival", "impact", "plateau", "return", "rms"], exp, run):
    check(abs(r - e) < 0.005, f"{name}: {r} against the experiment's {e}")
finish()
PY
[ $? -eq 0 ] || fail=1
exit $fail
