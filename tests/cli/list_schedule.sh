#!/usr/bin/env bash
# A run's answer does not depend on when its neighbour lists were rebuilt: the Verlet skin only decides
# how often the lists are remade, so with no skin (a rebuild every step) the same states follow bitwise.
# On the baffle scene, whose thin plate hides the particles on one side from those on the other, the
# plate's screen used to be decided at each rebuild and kept for the list's life: the baffle's impulse
# over 0.5 s moved by percents with the skin and with the re-ordering cadence (-partition_interval).
# Re-ordering changes sums' order: the same answer to round-off.
#   usage: list_schedule.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
scene="-case scene -scene_file $src/cases/scenes/baffle_sloshing.yaml -nx 20 -t_end 0.8 -progress 0 -threads 1 -output_interval 0"
for s in isph wcsph; do
  expect_ok $scene -solver $s -output_dir "$tmp/$s"
  expect_ok $scene -solver $s -neighbour_skin 0 -output_dir "$tmp/$s-skin0"
  expect_ok $scene -solver $s -partition_interval 0 -output_dir "$tmp/$s-once"
  cmp -s "$tmp/$s/timeseries.csv" "$tmp/$s-skin0/timeseries.csv" && echo "ok: $s: no skin, the same run bitwise" ||
    { echo "FAIL: $s: the run depends on the Verlet skin"; fail=1; }
done
/usr/bin/python3 - "$tmp" <<'PY' || fail=1
import csv, sys
tmp = sys.argv[1]
ok = True
for s in ("isph", "wcsph"):
    def impulse(run):
        rows = list(csv.DictReader(open(f"{tmp}/{run}/timeseries.csv")))
        return sum(float(r["force_baffle_x"]) * float(r["dt"]) for r in rows)
    a, b = impulse(s), impulse(s + "-once")
    good = abs(a - b) <= 1e-6 * abs(a)
    print(("ok: " if good else "FAIL: ") + f"{s}: impulse {a:.9g}, re-ordered once only {b:.9g}")
    ok &= good
sys.exit(0 if ok else 1)
PY
exit $fail
