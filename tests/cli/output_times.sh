#!/usr/bin/env bash
# -output_times exact: every frame at a multiple of -output_interval (to round-off), in both schemes,
# the steps before each frame evened out (no step shorter than the rest's half); a restart from a
# frame's checkpoint continues the run byte for byte; the default writes at the first step past each time.
#   usage: output_times.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
for s in isph wcsph; do
  run="-case dam_break -nx 10 -solver $s -t_end 0.3 -output_interval 0.07 -progress 0 -threads 1"
  expect_ok $run -output_times exact -output_dir "$tmp/$s"
  expect_ok $run -output_dir "$tmp/$s-step"
  # The checkpoint written with the frame at t = 0.14, resumed in a copy: the rows after it again.
  expect_ok $run -output_times exact -t_end 0.14 -output_dir "$tmp/$s-half"
  expect_ok $run -output_times exact -restart "$tmp/$s-half/checkpoint.bin"
  cmp -s "$tmp/$s/timeseries.csv" "$tmp/$s-half/timeseries.csv" && echo "ok: $s: resumed at a frame, the same rows" ||
    { echo "FAIL: $s: the resumed run's rows differ"; fail=1; }
done
PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp" <<'PY' || fail=1
import csv, re, sys
tmp = sys.argv[1]
from checks import check, finish
def frame_times(run):
    return [float(t) for t in re.findall(r'timestep="([^"]+)"', open(f"{tmp}/{run}/particles.pvd").read())]
want = [0, 0.07, 0.14, 0.21, 0.28, 0.3]
for s in ("isph", "wcsph"):
    got = frame_times(s)
    check(len(got) == len(want) and all(abs(a - b) < 1e-12 for a, b in zip(got, want)),
          f"{s}: frames at {', '.join(f'{t:.15g}' for t in got)}")
    dts = [float(r["dt"]) for r in csv.DictReader(open(f"{tmp}/{s}/timeseries.csv"))]
    check(min(dts[:-1]) > 0.5 * max(dts), f"{s}: steps from {min(dts):.3g} to {max(dts):.3g}, none a sliver")
    step = frame_times(f"{s}-step")
    check(any(abs(a - b) > 1e-6 for a, b in zip(step, want)), f"{s}: by default the frames land on steps")
finish()
PY
expect_error "-output_times.*step.*exact" -case dam_break -nx 10 -t_end 0.1 -progress 0 -output_times nearest \
  -output_dir "$tmp/bad"
exit $fail
