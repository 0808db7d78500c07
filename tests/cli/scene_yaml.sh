#!/usr/bin/env bash
# YAML scenes (-case scene -scene_file FILE.yaml): the example scenes, sampled at the run's -nx, run a
# few steps with ISPH and WCSPH; the fluid grows as nx^2; the spacing comes from exactly one place; a
# bad file is refused with one line naming the file, the line and the key.
#   usage: scene_yaml.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
block="$src/cases/scenes/falling_block.yaml"
short="-case scene -progress 0 -threads 1"

for solver in isph wcsph; do
  expect_ok $short -scene_file "$block" -nx 20 -solver $solver -max_steps 5 -output_dir "$tmp/block20-$solver"
  expect_json "$tmp/block20-$solver/summary.json" "s['status'] == 'completed' and s['steps'] == 5 and s['dx'] == 0.05 and s['parameters']['fluid_particles'] == 108 and s['parameters']['bodies'] == {'cylinder': 16}" "falling block, nx 20, $solver: 5 steps, 108 fluid particles, the cylinder a body"
done
# Half the spacing, four times the fluid (0.4 x 0.3 block and 1 x 0.15 pool: 432 at nx 40). The walls
# are 3 layers deep at every spacing, so they grow as nx.
expect_ok $short -scene_file "$block" -scene_dx 0.025 -max_steps 1 -output_dir "$tmp/block40"
expect_json "$tmp/block40/summary.json" "s['parameters']['fluid_particles'] == 4 * 108 and 1.8 < s['parameters']['fixed_wall_particles'] / 266 < 2.2 and abs(s['parameters']['wall_thickness_dx'] - 3) < 1e-9" "falling block, dx 0.025: four times the fluid of nx 20, walls 3 dx"
# At nx 10 the cylinder (radius 0.12) is 2 dx across, thinner than the kernel's 3 dx support.
expect_error "scene file '$block': the walls near \(0.45, 0.45\) are 2 dx thick, thinner than the kernel support \(3 dx\); the solid there is thinner than the support at this spacing" $short -scene_file "$block" -nx 10 -max_steps 1 -output_dir "$tmp/refused"
# The same scene at nx 10 with a kernel of 2 dx support (walls 2 layers): a quarter of nx 20's fluid,
# but for the lattice points that fall on the pool's and the block's faces (y = 0.15, 0.75, 1.05),
# which count as inside: 36 particles.
expect_ok $short -scene_file "$block" -nx 10 -h_over_dx 1 -max_steps 1 -output_dir "$tmp/block10"
expect_json "$tmp/block10/summary.json" "s['parameters']['fluid_particles'] == 36 and abs(s['parameters']['wall_thickness_dx'] - 2) < 1e-9" "falling block, nx 10: 36 fluid particles, walls 2 dx for a 2 dx support"

# The 3D scene: a dam break onto a ball.
expect_ok $short -scene_file "$src/cases/scenes/dam_break_sphere.yaml" -nx 20 -max_steps 3 -output_dir "$tmp/sphere"
expect_json "$tmp/sphere/summary.json" "s['status'] == 'completed' and s['dim'] == 3 and s['parameters']['fluid_particles'] == 6 * 10 * 8 and s['parameters']['bodies']['ball'] > 0" "3D dam break onto a ball, nx 20: 480 fluid particles"

# A 3D body from an STL surface (a cube, written here), turning and oscillating in a tank of water:
# both schemes run it, and timeseries.csv has its force along z and its moment about three axes.
python3 - "$tmp/cube.stl" <<'PY'
import itertools, sys
lo, hi = (0.3, 0.3, 0.15), (0.7, 0.7, 0.55)
corner = lambda b: tuple(hi[a] if b >> a & 1 else lo[a] for a in range(3))
faces = [(0, 2, 6, 4), (1, 5, 7, 3), (0, 4, 5, 1), (2, 3, 7, 6), (0, 1, 3, 2), (4, 6, 7, 5)]
with open(sys.argv[1], "w") as f:
    f.write("solid cube\n")
    for q in faces:
        for tri in ((q[0], q[1], q[2]), (q[0], q[2], q[3])):
            f.write(" facet normal 0 0 0\n  outer loop\n")
            for b in tri:
                f.write("   vertex %g %g %g\n" % corner(b))
            f.write("  endloop\n endfacet\n")
    f.write("endsolid cube\n")
PY
cat >"$tmp/cube.yaml" <<'YAML'
dimension: 3
box: [-0.3, 1.3, -0.3, 1.3, -0.3, 1.3]
gravity: [0, 0, -1]
free_surface: true
regions:
  - {role: wall, shape: difference, of: [{box: [-1, 2, -1, 2, -1, 2]}, {box: [0, 1, 0, 1, 0, 3]}]}
  - {role: fluid, shape: box, bounds: [0, 1, 0, 1, 0, 0.7], pressure: hydrostatic}
  - {role: body, name: cube, shape: mesh, file: cube.stl,
     motion: {type: sinusoidal, amplitude: [0.02, 0, 0], period: 1, phase: -90,
              rotation: {type: sinusoidal, amplitude: 10, period: 1, phase: -90, centre: [0.5, 0.5, 0.35], axis: [0, 0, 1]}}}
YAML
for solver in isph wcsph; do
  expect_ok $short -scene_file "$tmp/cube.yaml" -nx 12 -solver $solver -max_steps 5 -output_dir "$tmp/cube-$solver"
  expect_json "$tmp/cube-$solver/summary.json" "s['status'] == 'completed' and s['parameters']['bodies']['cube'] > 0 and s['wall_groups']['cube']['particles'] > 0" "STL cube body, 3D, $solver: runs"
  python3 - "$tmp/cube-$solver/timeseries.csv" <<'PY' || { echo "FAIL: the cube's force columns ($solver)"; fail=1; }
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
names = ["force_cube_z", "force_cube_pressure_z", "moment_cube_x", "moment_cube_y", "moment_cube_z", "force_walls_z"]
assert len(rows) == 5 and all(n in rows[0] for n in names), rows[0].keys()
assert all(math.isfinite(float(r[n])) for r in rows for n in names)
assert float(rows[-1]["force_cube_z"]) > 0  # held under water, pushed up
PY
done

# The spacing: -nx or -scene_dx, not both; none at all is refused; -nx is refused for a .vtp scene.
expect_error "-nx and -scene_dx both set the particle spacing; give one of them" $short -scene_file "$block" -nx 20 -scene_dx 0.05 -output_dir "$tmp/refused"
expect_error "scene file '$block': gives no particle spacing; pass -nx N \(dx = 1/N\) or -scene_dx, or add dx: to the file" $short -scene_file "$block" -output_dir "$tmp/refused"
"$src/scripts/make-scene" cavity --nx 8 -o "$tmp/cavity.vtp" >/dev/null || { echo "FAIL: make-scene"; fail=1; }
expect_error "-nx sets the spacing of YAML scenes; the particles of '$tmp/cavity.vtp' are fixed: remove -nx" $short -scene_file "$tmp/cavity.vtp" -nx 8 -output_dir "$tmp/refused"

# A misspelt key and an unknown shape: the line, the key, the fix.
printf 'dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0, 1, 0, 1]}, velocty: [1, 0]}\n' >"$tmp/key.yaml"
expect_error "scene file '$tmp/key.yaml': line 3, regions\[0\]: unknown key 'velocty'; the keys here are role, shape, velocity, pressure" $short -scene_file "$tmp/key.yaml" -nx 10 -output_dir "$tmp/refused"
printf 'dimension: 2\nregions:\n  - {role: fluid, shape: {square: [0, 1, 0, 1]}}\n' >"$tmp/shape.yaml"
expect_error "scene file '$tmp/shape.yaml': line 3, regions\[0\].shape: unknown shape 'square'; use one of box, circle" $short -scene_file "$tmp/shape.yaml" -nx 10 -output_dir "$tmp/refused"
printf 'dimension: 3\nregions: [\n' >"$tmp/syntax.yml"
expect_error "scene file '$tmp/syntax.yml': line [0-9]+, column [0-9]+: YAML syntax error" $short -scene_file "$tmp/syntax.yml" -nx 10 -output_dir "$tmp/refused"
# A wall's slip condition: free or no_slip, and only on walls and bodies.
printf 'dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0, 1, 0, 1]}, slip: free}\n' >"$tmp/slip_fluid.yaml"
expect_error "scene file '$tmp/slip_fluid.yaml': line 3, regions\[0\].slip: is given for fluid; only walls and bodies have a slip condition" $short -scene_file "$tmp/slip_fluid.yaml" -nx 10 -output_dir "$tmp/refused"
printf 'dimension: 2\nregions:\n  - {role: wall, shape: {box: [0, 1, 0, 1]}, slip: sticky}\n' >"$tmp/slip_value.yaml"
expect_error "scene file '$tmp/slip_value.yaml': line 3, regions\[0\].slip: is not free or no_slip; give one of those" $short -scene_file "$tmp/slip_value.yaml" -nx 10 -output_dir "$tmp/refused"
# A wall group's own pressure form: adami or continued, and only on walls and bodies.
printf 'dimension: 2\nregions:\n  - {role: fluid, shape: {box: [0, 1, 0, 1]}, wall_pressure: continued}\n' >"$tmp/form_fluid.yaml"
expect_error "scene file '$tmp/form_fluid.yaml': line 3, regions\[0\].wall_pressure: is given for fluid; only walls and bodies continue the fluid's pressure" $short -scene_file "$tmp/form_fluid.yaml" -nx 10 -output_dir "$tmp/refused"
printf 'dimension: 2\nregions:\n  - {role: wall, shape: {box: [0, 1, 0, 1]}, wall_pressure: mirror}\n' >"$tmp/form_value.yaml"
expect_error "scene file '$tmp/form_value.yaml': line 3, regions\[0\].wall_pressure: is not adami or continued; give one of those \(-help, -wall_pressure\)" $short -scene_file "$tmp/form_value.yaml" -nx 10 -output_dir "$tmp/refused"
[ -e "$tmp/refused" ] && { echo "FAIL: a refused scene created its output directory"; fail=1; }
exit $fail
