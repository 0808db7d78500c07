#!/usr/bin/env bash
# Free bodies (src/boundary/free_body.hpp) on cases/scenes/floating_box.yaml, a box of half the water's
# density released above where it floats, both schemes at nx 20 in a viscous fluid (nu 0.1, so that it
# comes to rest by t = 3): its draft at rest against Archimedes (scripts/floating-check); a disk settling
# between two walls against Faxen's terminal velocity (scripts/settling-check); a box dropped on a dry
# floor held by the contact (src/boundary/body_contact.hpp), and one dropped onto another; a restart that
# equals the uninterrupted run bit for bit (ISPH and WCSPH), 2 ranks against 1, and one-line refusals
# of free bodies that cannot be.   usage: free_bodies.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mpiexec="${MPIEXEC:-mpiexec}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
fail=0
source "$(dirname "$0")/lib/expect.sh"
scene="$src/cases/scenes/floating_box.yaml"
quick="-case scene -scene_file $scene -nx 20 -progress 0 -threads 1"
for s in isph wcsph; do
  expect_ok $quick -solver $s -nu 0.1 -t_end 3 -output_interval 1 -output_dir "$tmp/rest_$s"
  # Stopped mid-run and continued: the body's state travels in the checkpoint.
  expect_ok $quick -solver $s -t_end 0.4 -output_interval 1 -output_dir "$tmp/full_$s"
  expect_ok $quick -solver $s -t_end 0.4 -output_interval 1 -max_steps 60 -output_dir "$tmp/half_$s"
  expect_ok $quick -solver $s -t_end 0.4 -output_interval 1 -restart "$tmp/half_$s/checkpoint.bin" \
    -output_dir "$tmp/resumed_$s"
done
# A disk settling between two walls in Stokes flow (cases/scenes/settling_disk.yaml), ISPH at nx 40.
expect_ok -case scene -scene_file "$src/cases/scenes/settling_disk.yaml" -nx 40 -progress 0 -threads 1 -solver isph \
  -t_end 1 -output_interval 1 -output_dir "$tmp/settling"
# Contact (src/boundary/body_contact.hpp): a box dropped 0.3 onto a dry floor, the scene's water held
# apart behind a wall; it lands and comes to rest on the floor, the contact carrying its weight.
cat > "$tmp/drop.yaml" <<'YAML'
dimension: 2
box: [-0.2, 2.2, -0.2, 1.2]
gravity: [0, -9.81]
nu: 1.0e-6
rho0: 1000
free_surface: true
t_end: 1.5
regions:
  - {role: wall, shape: difference, of: [{box: [-0.2, 2.2, -0.2, 1.2]}, {box: [0, 2, 0, 1.3]}]}
  - {role: wall, shape: box, bounds: [0.5, 0.7, 0, 0.3]}
  - {role: fluid, shape: box, bounds: [0, 0.5, 0, 0.1], pressure: hydrostatic}
  - {role: body, name: box, shape: box, bounds: [1.0, 1.4, 0.3, 0.5], density: 500, motion: {type: free}}
YAML
for s in isph wcsph; do
  expect_ok -case scene -scene_file "$tmp/drop.yaml" -nx 20 -progress 0 -threads 1 -solver $s -output_interval 1.5 \
    -output_dir "$tmp/drop_$s"
done
# Body on body: a box dropped onto another resting on the dry floor; the lower box's net contact is its
# own weight (the floor carries both, the upper box presses down with its own: Newton's third law
# between the two bodies' pair forces).
sed -e 's/name: box, shape: box, bounds: \[1.0, 1.4, 0.3, 0.5\]/name: base, shape: box, bounds: [1.0, 1.4, 0.02, 0.22]/' \
  "$tmp/drop.yaml" >"$tmp/stack.yaml"
echo "  - {role: body, name: top, shape: box, bounds: [1.1, 1.3, 0.3, 0.5], density: 500, motion: {type: free}}" \
  >>"$tmp/stack.yaml"
for s in isph wcsph; do
  expect_ok -case scene -scene_file "$tmp/stack.yaml" -nx 20 -progress 0 -threads 1 -solver $s -output_interval 1.5 \
    -output_dir "$tmp/stack_$s"
done
"$mpiexec" -n 2 "$sph" $quick -solver isph -t_end 0.4 -output_interval 1 -output_dir "$tmp/ranks2" >"$tmp/ranks2.log" 2>&1 ||
  { echo "FAIL: 2 ranks"; tail -3 "$tmp/ranks2.log"; fail=1; }

PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp" "$src" <<'PY' || fail=1
import csv, json, subprocess, sys
tmp, src = sys.argv[1:3]
from checks import check, finish
# Bounds at nx 20 from docs/verification/free_bodies.md (there: ISPH +0.64 %, WCSPH +1.7 %).
for s, bound in (("isph", 0.015), ("wcsph", 0.03)):
    out = subprocess.run([f"{src}/scripts/floating-check", f"{tmp}/rest_{s}", "--window", "1"], capture_output=True, text=True)
    if out.returncode != 0:
        check(False, f"{s}: floating-check: {out.stderr.strip()}"); continue
    f = json.loads(out.stdout)
    check(abs(f["draft_error"]) < bound, f"{s}: draft at rest {f['draft']:.5f} within {bound:.1%} of Archimedes' "
          f"{f['archimedes']:.5f} ({f['draft_error']:+.2%})")
    check(f["y_range_in_window"] < 2e-3, f"{s}: at rest: the box moves {f['y_range_in_window']:.1e} in the last second")
out = subprocess.run([f"{src}/scripts/settling-check", f"{tmp}/settling", "--window", "0.3"], capture_output=True, text=True)
if out.returncode != 0:
    check(False, f"settling-check: {out.stderr.strip()}")
else:
    f = json.loads(out.stdout)  # docs/verification/free_bodies.md: -1.3 % at nx 40
    check(abs(f["error"]) < 0.03, f"settling disk: terminal velocity {f['terminal_velocity']:.4e} within 3 % of "
          f"Faxen's {f['faxen']:.4e} ({f['error']:+.2%})")
# The contact's static sinking: 4 rows over 1 row touching, 1 % of dx each (body_contact.hpp): 0.002.
for s in ("isph", "wcsph"):
    rows = list(csv.DictReader(open(f"{tmp}/drop_{s}/timeseries.csv")))
    late = [r for r in rows if float(r["t"]) > 1.0]
    bottom = [float(r["box_y"]) - 0.1 for r in rows]
    rest = [float(r["box_y"]) - 0.1 for r in late]
    carried = sum(float(r["box_contact_y"]) for r in late) / len(late)
    check(min(bottom) > -0.5 * 0.05, f"{s} drop: the box sinks at most {-min(bottom):.4f} (< dx / 2) into the floor")
    check(all(abs(b + 0.002) < 0.0025 for b in rest), f"{s} drop: at rest on the floor (bottom {rest[-1]:+.4f}, "
          "0.002 in by the contact's stiffness)")
    check(abs(carried / 392.4 - 1) < 0.01, f"{s} drop: the contact carries the weight, {carried:.1f} of 392.4 N")
# The stack at rest (t > 1): each contact carries what rests on it, and each sinks as body_contact.hpp
# says: rows times 1 % of dx times its load over the body's own weight, twice that between two free
# bodies (the pair's reduced mass): the base 4 x 0.0005 x 1.5 = 0.003 into the floor, the top box
# 4 x 0.0005 x 2 = 0.004 into the base.
for s in ("isph", "wcsph"):
    rows = list(csv.DictReader(open(f"{tmp}/stack_{s}/timeseries.csv")))
    late = [r for r in rows if float(r["t"]) > 1.0]
    mean = lambda key: sum(float(r[key]) for r in late) / len(late)
    top, base = mean("top_contact_y"), mean("base_contact_y")
    check(abs(top / 196.2 - 1) < 0.01, f"{s} stack: the base carries the top box's weight, {top:.1f} of 196.2 N")
    check(abs(base / 392.4 - 1) < 0.01, f"{s} stack: the base's net contact is its own weight, {base:.1f} of 392.4 N")
    gap = mean("top_y") - mean("base_y") - 0.2
    check(abs(gap + 0.004) < 2e-4, f"{s} stack: the top box rests {-gap:.5f} into the base (0.004)")
    check(abs(mean("base_y") - 0.1 + 0.003) < 2e-4, f"{s} stack: the base rests {0.1 - mean('base_y'):.5f} into the floor (0.003)")
    check(min(float(r["top_y"]) - float(r["base_y"]) - 0.2 for r in rows) > -0.5 * 0.05,
          f"{s} stack: the landing never takes the top box dx / 2 into the base")

# The frames: the body's surface where the body is, and each particle's body.
import glob, vtk
from vtk.util.numpy_support import vtk_to_numpy
def read(path):
    r = vtk.vtkXMLPolyDataReader(); r.SetFileName(path); r.Update(); return r.GetOutput()
surface = vtk_to_numpy(read(sorted(glob.glob(f"{tmp}/rest_isph/body_box_*.vtp"))[-1]).GetPoints().GetData())
y_end = float(list(csv.DictReader(open(f"{tmp}/rest_isph/timeseries.csv")))[-1]["box_y"])
mid = 0.5 * (surface[:, 1].min() + surface[:, 1].max())
check(abs(mid - y_end) < 1e-3, f"body_box.pvd: the surface's middle {mid:.4f} where the box is ({y_end:.4f})")
body = vtk_to_numpy(read(sorted(glob.glob(f"{tmp}/rest_isph/particles_*.vtp"))[-1]).GetPointData().GetArray("body"))
check((body == 0).sum() == 32 and (body == -1).sum() == len(body) - 32, "frames: the box's 32 particles have body 0")
last = lambda run: list(csv.DictReader(open(f"{tmp}/{run}/timeseries.csv")))[-1]
for s in ("isph", "wcsph"):
    a, b = last(f"full_{s}"), last(f"resumed_{s}")
    check(a == b, f"{s}: the restart's last row equals the uninterrupted run's, every column bitwise")
    check(float(a["box_y"]) < 0.55 - 1e-3, f"{s}: the box moved (y {float(a['box_y']):.4f} from 0.55)")
a, b = last("full_isph"), last("ranks2")
dy = abs(float(a["box_y"]) - float(b["box_y"]))
check(dy < 5e-4, f"2 ranks: the box's height within 5e-4 of 1 rank's (off by {dy:.1e})")
s = json.load(open(f"{tmp}/rest_isph/summary.json"))
check(abs(s["free_bodies"]["box"]["mass"] - 40.0) < 1e-9, "summary.json: the box's mass, 500 kg/m^3 x 0.08 m^2")
check(s["wall_groups"]["box"]["moment_about"] == "centre of mass", "summary.json: a free body's moment is about its centre of mass")
finish()
PY

# Free bodies that cannot be are refused in one line naming the key.
bad() { sed "$1" "$scene" > "$tmp/bad.yaml"; }
run_bad() { expect_error "$1" -case scene -scene_file "$tmp/bad.yaml" -nx "${2:-10}" -output_dir "$tmp/bad"; }
bad 's/density: 500/density: -5/';                 run_bad "density: is -5; give a positive density"
bad 's/density: 500/mass: 0/';                     run_bad "mass: is 0; give a positive mass"
bad 's/density: 500, //';                          run_bad "motion: makes a free body with no mass; add density"
bad 's/density: 500/density: 500, mass: 40/';      run_bad "mass: is given with density:; give one of them"
bad 's/{type: free}/{type: free, fixed: [q]}/';    run_bad "fixed: names 'q', which is no axis; give x, y or rotation"
bad 's/{type: free}/{type: free, fixed: [x], hinge: [1, 0.45]}/'; run_bad "hinge: is given with fixed:"
bad 's/, motion: {type: free}//';                  run_bad "density: is given for a body the fluid does not move"
bad 's/bounds: \[0.8, 1.2, 0.45, 0.65\]/bounds: [0.8, 1.2, -0.1, 0.1]/'
run_bad "is free body 'box', which starts inside regions\[0\] \(a wall\); move it clear" 20
bad '/role: fluid/d';                              run_bad "makes body 'box' free in a scene with no fluid region"
exit $fail
