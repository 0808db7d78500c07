#!/usr/bin/env bash
# Thin plates (shape: plate in a 2D YAML scene): a plate with no thickness splits a periodic channel in
# two, and each half must be the channel 0.5 wide between ordinary walls, to round-off (the plate's
# layers and the neighbour lists' screen make it a wall on each side), for both schemes and on 2 ranks;
# the flow is Poiseuille's; a plate that cannot be built is refused with one line.
#   usage: thin_plate.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
short="-case scene -progress 0 -threads 1 -output_interval 0 -checkpoint_interval 0"
split="$src/cases/scenes/split_channel.yaml"
cat >"$tmp/half.yaml" <<'YAML'
dimension: 2
box: [0, 1, -0.2, 0.7]
periodic: x
physics: {gravity: [0.8, 0], nu: 0.1, rho0: 1, free_surface: false, t_end: 2, U: 0.25}
regions:
  - {role: wall, shape: box, bounds: [-1, 2, -1, 0]}
  - {role: wall, shape: box, bounds: [-1, 2, 0.5, 2]}
  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.5]}
YAML
# The two halves together carry twice the half channel's momentum and kinetic energy, step by step, to
# the relative tolerance $4 (round-off on one rank; on two the sums add in another order, and the
# differences of 1e-16 a step reach 1e-10 over the run's thousand steps).
compare_halves() {
  python3 - "$1/timeseries.csv" "$2/timeseries.csv" "$3" "$4" <<'PY' || { echo "FAIL: $3"; fail=1; }
import csv, sys
a, b = (list(csv.DictReader(open(f))) for f in sys.argv[1:3])
assert len(a) == len(b) and len(a) > 100, (len(a), len(b))
worst = max(abs(float(x[k]) - 2 * float(y[k])) / max(1e-300, abs(2 * float(y[k])))
            for x, y in zip(a, b) for k in ("kinetic_energy", "momentum_x"))
assert worst < float(sys.argv[4]), worst
print("ok: %s (largest relative difference %.1e)" % (sys.argv[3], worst))
PY
}
for solver in isph wcsph; do
  expect_ok $short -scene_file "$split" -nx 20 -solver $solver -output_dir "$tmp/split-$solver"
  expect_ok $short -scene_file "$tmp/half.yaml" -nx 20 -solver $solver -output_dir "$tmp/half-$solver"
  compare_halves "$tmp/split-$solver" "$tmp/half-$solver" "split channel, $solver: each half is the channel between walls" 1e-12
  # Poiseuille's flux, g h^3 / (12 nu) a half, is 1/6 for the two: within the half channel's own wall error
  # at 10 particles across (+3.1 % at nx 20; docs/verification/thin_plate.md).
  python3 - "$tmp/split-$solver/timeseries.csv" "$solver" <<'PY' || { echo "FAIL: split channel, $solver: Poiseuille's flux"; fail=1; }
import csv, sys
last = list(csv.DictReader(open(sys.argv[1])))[-1]
flux = float(last["momentum_x"])
assert float(last["t"]) == 2 and abs(flux * 6 - 1) < 0.035, (last["t"], flux)
print("ok: split channel, %s: flux %.4f, Poiseuille's 1/6 within 3.5 %%" % (sys.argv[2], flux))
PY
done
if [ -n "${MPIEXEC:-}" ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  extra=""; "$MPIEXEC" --help 2>&1 | grep -q oversubscribe && extra="--oversubscribe"
  if "$MPIEXEC" $extra -n 2 "$sph" $short -scene_file "$split" -nx 20 -solver wcsph -output_dir "$tmp/split-2" >"$tmp/stdout" 2>"$tmp/stderr"; then
    compare_halves "$tmp/split-2" "$tmp/half-wcsph" "split channel, wcsph on 2 ranks: each half is the channel between walls" 1e-8
  else echo "FAIL: the split channel on 2 ranks:"; cat "$tmp/stderr"; fail=1; fi
fi

# A plate standing on the floor holds still water 0.6 deep on its left and 0.3 on its right: at rest
# (no kinetic energy to round-off in ISPH, a trace in WCSPH) with the force rho g (0.6^2 - 0.3^2) / 2
# = 1324.35 N/m every step. Before the screen went on through the floor, the floor's particles beside
# the plate's foot took their pressure from both sides and ISPH's first step gave 1050.
cat >"$tmp/dam.yaml" <<'YAML'
dimension: 2
box: [-0.3, 2.3, -0.3, 1.3]
physics: {gravity: [0, -9.81], nu: 1.0e-6, rho0: 1000, free_surface: true, t_end: 0.1}
regions:
  - {role: wall, shape: difference, of: [{box: [-0.3, 2.3, -0.3, 1.3]}, {box: [0, 2, 0, 1]}]}
  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.6], pressure: hydrostatic}
  - {role: fluid, shape: box, bounds: [1, 2, 0, 0.3], pressure: hydrostatic}
  - {role: {body: dam}, shape: plate, from: [1, 0], to: [1, 0.8]}
YAML
for solver in isph wcsph; do
  expect_ok $short -scene_file "$tmp/dam.yaml" -nx 20 -solver $solver -output_dir "$tmp/dam-$solver"
  python3 - "$tmp/dam-$solver/timeseries.csv" "$solver" <<'PY' || { echo "FAIL: water held by a plate, $solver"; fail=1; }
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
exact = 1000 * 9.81 * (0.6**2 - 0.3**2) / 2
force = [float(r["force_dam_x"]) for r in rows]
mean = sum(force) / len(force)
kinetic = max(float(r["kinetic_energy"]) for r in rows)
if sys.argv[2] == "isph":  # every step, and still water stays still
    worst = max(abs(f / exact - 1) for f in force)
    assert worst < 1e-3 and kinetic < 1e-9, (worst, kinetic)
else:  # its weakly compressible water rings about the force
    worst = abs(mean / exact - 1)
    assert worst < 0.01 and kinetic < 0.01, (worst, kinetic)
print("ok: water held by a plate, %s: force within %.1e of rho g (h1^2 - h2^2) / 2, kinetic energy %.1e" % (sys.argv[2], worst, kinetic))
PY
done
# A tank that moves at constant velocity, a plate standing in it, the water moving with it: Galilean
# invariance, so the water stays at the tank's velocity and its weight rests on the tank. A body's
# plate moves with the body (its screen too): before it did, the screen stayed where the plate had been,
# ISPH's water left the tank's velocity by 3.8 and WCSPH's blew up by t = 0.37. The bounds: ISPH 2e-6
# measured; WCSPH 5.9e-3, the trace its still water keeps in the tank at rest too (3.8e-3).
cat >"$tmp/tank.yaml" <<'YAML'
dimension: 2
box: [-0.5, 3, -0.3, 1.3]
physics: {gravity: [0, -9.81], nu: 1.0e-6, rho0: 1000, free_surface: true, t_end: 0.5, U: 2}
regions:
  - {role: body, name: tank, shape: difference, of: [{box: [-0.3, 2.3, -0.3, 1.0]}, {box: [0, 2, 0, 1.2]}],
     motion: {type: constant, velocity: [0.5, 0]}}
  - {role: fluid, shape: box, bounds: [0, 2, 0, 0.4], pressure: hydrostatic, velocity: [0.5, 0]}
  - {role: {body: tank}, shape: plate, from: [1, 0], to: [1, 0.6]}
YAML
for solver in isph wcsph; do
  expect_ok -case scene -progress 0 -threads 1 -checkpoint_interval 0 -output_interval 0.5 -scene_file "$tmp/tank.yaml" \
    -nx 20 -solver $solver -output_dir "$tmp/tank-$solver"
  /usr/bin/python3 - "$tmp/tank-$solver" "$solver" <<'PY' || { echo "FAIL: a moving tank with a plate, $solver"; fail=1; }
import csv, sys
import vtk
from vtk.util.numpy_support import vtk_to_numpy
run, solver = sys.argv[1:3]
r = vtk.vtkXMLPolyDataReader(); r.SetFileName(f"{run}/particles_00001.vtp"); r.Update()
d = r.GetOutput().GetPointData()
kind, v = vtk_to_numpy(d.GetArray("kind")), vtk_to_numpy(d.GetArray("velocity"))
off = max(max(abs(v[i, 0] - 0.5), abs(v[i, 1])) for i in range(len(kind)) if kind[i] == 0)
rows = list(csv.DictReader(open(f"{run}/timeseries.csv")))
weight = 1000 * 9.81 * 2 * 0.4
fy = sum(float(x["force_tank_y"]) for x in rows) / len(rows)
bound = 1e-4 if solver == "isph" else 0.02
assert off < bound and abs(-fy / weight - 1) < 0.01, (off, fy)
print("ok: a moving tank with a plate, %s: the water within %.1e of the tank's velocity, its mean weight on the tank "
      "%.1f N/m against %.1f" % (solver, off, -fy, weight))
PY
done

# A plate too short for a row of layers at this spacing (0.01 long at dx 0.05) is left out, and the
# plates after it keep their own screens: the run is the one without it, byte for byte. (Its layers'
# labels once counted it, and the dam's layers named a plate that the screens did not have: a blow-up at
# step 6.)
sed 's/^  - {role: {body: dam}/  - {role: wall, shape: plate, from: [0.2, 0.9], to: [0.2, 0.91]}\n  - {role: {body: dam}/' \
  "$tmp/dam.yaml" >"$tmp/dam-short.yaml"
grep -q "to: \[0.2, 0.91\]" "$tmp/dam-short.yaml" || { echo "FAIL: the short plate's scene was not written"; fail=1; }
expect_ok $short -scene_file "$tmp/dam-short.yaml" -nx 20 -solver isph -output_dir "$tmp/dam-short"
if cmp -s "$tmp/dam-short/timeseries.csv" "$tmp/dam-isph/timeseries.csv"; then
  echo "ok: a plate too short for a row leaves the next plate's run unchanged"
else echo "FAIL: a plate too short for a row changed the next plate's run"; fail=1; fi

plate_scene() {  # <dimension> <plate region> <file>
  printf 'dimension: %s\nbox: [0, 1, 0, 1%s]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 1%s]}\n  - %s\n' \
    "$1" "$([ "$1" = 3 ] && echo ', 0, 1')" "$([ "$1" = 3 ] && echo ', 0, 1')" "$2" >"$3"
}
plate_scene 3 "{role: wall, shape: plate, from: [0, 0.5, 0], to: [1, 0.5, 0]}" "$tmp/plate3d.yaml"
expect_error "regions\[1\].shape.* is a plate, which only 2D scenes have" $short -scene_file "$tmp/plate3d.yaml" -nx 10 -max_steps 1 -output_dir "$tmp/r1"
plate_scene 2 "{role: {body: p}, shape: plate, from: [0, 0.5], to: [1, 0.5], density: 500, motion: {type: free}}" "$tmp/moving.yaml"
expect_error "regions\[1\]: is a plate of free body 'p'; a plate moves only with a prescribed motion" $short -scene_file "$tmp/moving.yaml" -nx 10 -max_steps 1 -output_dir "$tmp/r2"
plate_scene 2 "{role: fluid, shape: plate, from: [0, 0.5], to: [1, 0.5]}" "$tmp/fluid.yaml"
expect_error "is a plate of fluid" $short -scene_file "$tmp/fluid.yaml" -nx 10 -max_steps 1 -output_dir "$tmp/r3"
plate_scene 2 "{role: wall, shape: plate, from: [0, 0.5], to: [0, 0.5]}" "$tmp/point.yaml"
expect_error "is the plate's from point; give the plate a length" $short -scene_file "$tmp/point.yaml" -nx 10 -max_steps 1 -output_dir "$tmp/r4"
python3 - "$tmp/many.yaml" <<'PY'
import sys
with open(sys.argv[1], "w") as f:
    f.write("dimension: 2\nbox: [0, 1, 0, 1]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 1]}\n")
    for k in range(128):
        f.write("  - {role: wall, shape: plate, from: [%g, 0.5], to: [%g, 0.6]}\n" % (k / 128, k / 128))
PY
expect_error "regions\[128\]: is the 128th plate; a scene holds at most 127" $short -scene_file "$tmp/many.yaml" -nx 10 -max_steps 1 -output_dir "$tmp/r5"
exit $fail
