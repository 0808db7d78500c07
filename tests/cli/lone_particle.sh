#!/usr/bin/env bash
# A lone fluid particle beside a vertical no-slip wall falls: the walls' pressure continues the fluid's
# own pressure along the wall (src/boundary/adami_wall.hpp), so no hydrostatic column that is not there
# holds it up, and the pressure does no work on it (before: ISPH's particle hung, rising 6e-3 after its
# first step; WCSPH's fell with a fifth of gravity's work taken by the pressure). Both schemes with the
# same kernel share the viscous operator, so they reach the same terminal speed, where the wall's drag
# takes what gravity gives (docs/verification/free_surface.md, "Spray, and particles that leave").
#   usage: lone_particle.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
cat > "$tmp/lone.yaml" <<'YAML'
dimension: 2
box: [-0.3, 1.3, -0.3, 1.3]
physics: {gravity: [0, -1], nu: 0.01, rho0: 1, free_surface: true, t_end: 1.5}
regions:
  - {role: wall, shape: {difference: [{box: [-1, 2, -1, 2]}, {box: [0, 1, 0, 2]}]}}
  - {role: fluid, shape: {box: [0, 0.05, 0.6, 0.65]}, pressure: 0}
YAML
common="-case scene -scene_file $tmp/lone.yaml -nx 20 -progress 0 -threads 1 -output_interval 0 -checkpoint_interval 0 -wall_pressure continued"
expect_ok $common -solver isph -output_dir "$tmp/isph"
expect_ok $common -solver wcsph -kernel wendland_c2 -output_dir "$tmp/wcsph"
expect_ok $common -solver wcsph -output_dir "$tmp/wcsph-quintic"  # its free-surface default kernel

PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp" <<'PY' || fail=1
import csv, sys
tmp = sys.argv[1]
from checks import check, finish
mass = 0.05 ** 2
speed = {}
for run in ("isph", "wcsph", "wcsph-quintic"):
    rows = list(csv.DictReader(open(f"{tmp}/{run}/timeseries.csv")))
    last = rows[-1]
    v = -float(last["momentum_y"]) / mass
    earlier = min(rows, key=lambda r: abs(float(r["t"]) - 1.0))
    v_earlier = -float(earlier["momentum_y"]) / mass
    pressure, viscous = float(last["work_pressure"]), float(last["work_viscous"])
    speed[run] = v
    print(f"{run}: speed {v:.5f} at t = {last['t']} ({v_earlier:.5f} at t = 1), pressure's work {pressure:.2e}, "
          f"viscous {viscous:.2e}")
    check(v > 0.1, f"{run}: the particle falls (speed {v:.4f})")
    check(abs(pressure) < 1e-4 * abs(viscous), f"{run}: the pressure does no work on it ({pressure:.1e} against {viscous:.1e})")
    check(abs(v - v_earlier) < 0.02 * v, f"{run}: it has reached its terminal speed ({v_earlier:.5f} -> {v:.5f})")
# The terminal speed is g over the viscous drag's rate, the same operator and kernel in both schemes.
check(abs(speed["isph"] - speed["wcsph"]) < 0.005 * speed["isph"],
      f"ISPH and WCSPH with one kernel fall at one speed ({speed['isph']:.5f}, {speed['wcsph']:.5f})")
finish()
PY

# The same wall condition chosen by one wall group (wall_pressure: continued on the left wall) while the
# others keep the option's default (adami): a particle on the left wall falls as above, at the same
# speed; one on the right wall is held up by Adami's column.
for side in left right; do
  x=$([ $side = left ] && echo "0, 0.05" || echo "0.95, 1")
  cat > "$tmp/group_$side.yaml" <<YAML
dimension: 2
box: [-0.3, 1.3, -0.3, 1.3]
physics: {gravity: [0, -1], nu: 0.01, rho0: 1, free_surface: true, t_end: 1.5}
regions:
  - {role: wall, shape: {box: [-0.3, 0, -0.3, 1.3]}, wall_pressure: continued}
  - {role: wall, shape: {difference: [{box: [0, 1.3, -0.3, 1.3]}, {box: [0, 1, 0, 2]}]}}
  - {role: fluid, shape: {box: [$x, 0.6, 0.65]}, pressure: 0}
YAML
  expect_ok -case scene -scene_file "$tmp/group_$side.yaml" -nx 20 -progress 0 -threads 1 -output_interval 0 \
    -checkpoint_interval 0 -solver isph -output_dir "$tmp/group_$side"
done
PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp" <<'PY' || fail=1
import csv, sys
tmp = sys.argv[1]
from checks import check, finish
def speed(run):
    return -float(list(csv.DictReader(open(f"{tmp}/{run}/timeseries.csv")))[-1]["momentum_y"]) / 0.05 ** 2
both, left, right = speed("isph"), speed("group_left"), speed("group_right")
print(f"speed with every wall continued {both:.5f}, the left wall's group alone: on the left {left:.5f}, on the right {right:.5f}")
check(abs(left - both) < 1e-6 * both, f"the left wall's own choice lets its particle fall as the option does ({left:.6f}, {both:.6f})")
check(abs(right) < 0.1 * both, f"the right wall keeps the default and holds its particle ({right:.5f})")
finish()
PY
exit $fail
