#!/usr/bin/env bash
# scripts/force-spectrum on a made-up run: a force of 50 + 2t plus a 30 Hz ring of amplitude 10, in
# uneven steps, with c0 = 48 in summary.json (c0 / 4H = 30 Hz at H = 0.4). The ring is the whole
# fluctuation (the 0.1 average spans three of its periods and takes out the linear part): RMS 10/sqrt(2),
# its frequency 30 Hz, all its power near c0 / 4H.
#   usage: force_spectrum.sh <sph executable, unused> <source dir>
set -u
src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/run"
/usr/bin/python3 - "$tmp/run" <<'PY'
import json, math, sys
run = sys.argv[1]
with open(f"{run}/timeseries.csv", "w") as f:
    f.write("step,t,dt,force_baffle_x\n")
    t, k = 0.0, 0
    while t < 1.0:
        dt = 2e-4 if k % 2 else 3e-4
        t += dt; k += 1
        f.write(f"{k},{t!r},{dt!r},{50 + 2 * t + 10 * math.sin(2 * math.pi * 30 * t)!r}\n")
json.dump({"models": {"equation_of_state": {"c0": 48.0}}}, open(f"{run}/summary.json", "w"))
PY
out=$("$src/scripts/force-spectrum" "$tmp/run" --depth 0.4) || { echo "FAIL: force-spectrum exited non-zero"; exit 1; }
echo "$out"
PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$out" <<'PY'
import math, sys
from checks import check, finish
row = sys.argv[1].splitlines()[1].split()
rms, freq, c0, f0, share = float(row[1]), float(row[2]), float(row[3]), float(row[4]), float(row[5])
check(abs(rms / (10 / math.sqrt(2)) - 1) < 0.01, f"the ring's RMS {rms} against 10/sqrt(2) = 7.07")
check(abs(freq - 30) < 1.0, f"its strongest frequency {freq} Hz against 30")
check(abs(f0 - 30) < 1e-9 and share > 95, f"c0/4H {f0} Hz, {share} % of the power near it")
finish()
PY
