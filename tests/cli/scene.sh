#!/usr/bin/env bash
# Scenes from files (-case scene): every bad scene file is refused with one line naming the file and
# what is wrong, before anything is written; scripts/make-scene's scenes run with ISPH and WCSPH, in 2D
# and 3D, on 1 and 2 MPI ranks.   usage: scene.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mpiexec="${MPIEXEC:-mpiexec}"
fail=0
source "$(dirname "$0")/lib/expect.sh"
make_scene() { "$src/scripts/make-scene" "$@" >/dev/null || { echo "FAIL: make-scene $*"; fail=1; }; }
damage() { /usr/bin/python3 "$(dirname "$0")/lib/bad_scene.py" "$tmp/cavity.vtp" "$tmp/$1.vtp" "$1" || { echo "FAIL: bad_scene.py $1"; fail=1; }; }

make_scene cavity --nx 8 -o "$tmp/cavity.vtp"
short="-case scene -t_end 0.02 -progress 0 -threads 1 -output_dir $tmp/refused"
expect_error "-case scene needs -scene_file FILE" $short
expect_error "scene file '$tmp/missing.vtp': cannot be opened" $short -scene_file "$tmp/missing.vtp"
echo "not a scene" >"$tmp/text.vtp"
expect_error "scene file '$tmp/text.vtp': is not a VTK XML PolyData" $short -scene_file "$tmp/text.vtp"
for d in no_kind kind_5 nan outside no_fluid no_dx; do damage $d; done
expect_error "scene file '$tmp/no_kind.vtp': has no point array 'kind' \(.*0 fluid, 1 fixed wall, 2 moving wall\)" $short -scene_file "$tmp/no_kind.vtp"
expect_error "scene file '$tmp/kind_5.vtp': particle 3 has kind 5; kind must be 0 \(fluid\), 1 \(fixed wall\) or 2" $short -scene_file "$tmp/kind_5.vtp"
expect_error "scene file '$tmp/nan.vtp': particle 7 has a coordinate that is not a number" $short -scene_file "$tmp/nan.vtp"
expect_error "scene file '$tmp/outside.vtp': particle 7 at \(100, 0.5\) lies outside the box \[-0.5, 1.5\] along x" $short -scene_file "$tmp/outside.vtp"
expect_error "scene file '$tmp/no_fluid.vtp': has no fluid particle" $short -scene_file "$tmp/no_fluid.vtp"
expect_error "scene file '$tmp/no_dx.vtp': gives no particle spacing; add field data 'dx' or pass -scene_dx" $short -scene_file "$tmp/no_dx.vtp"
# A misspelt or malformed array would leave the lid at rest; a lid pushed into the fluid would never
# move: each refused, naming it.
for d in Velocity velocity_text velocity_1 lid_normal dx_inf t_end_negative; do damage $d; done
expect_error "scene file '$tmp/Velocity.vtp': has a point array 'Velocity', which is not read: the array is 'velocity' \(lower case\)" $short -scene_file "$tmp/Velocity.vtp"
expect_error "scene file '$tmp/velocity_text.vtp': point array 'velocity' is not numeric" $short -scene_file "$tmp/velocity_text.vtp"
expect_error "scene file '$tmp/velocity_1.vtp': point array 'velocity' has 1 component\(s\); give 2 or 3" $short -scene_file "$tmp/velocity_1.vtp"
expect_error "scene file '$tmp/lid_normal.vtp': moving-wall particle [0-9]+ at \(.*\) has velocity \(0, -1\), [0-9]+ degrees from the normal of the fluid beside it; .*give it a velocity along its wall" $short -scene_file "$tmp/lid_normal.vtp"
expect_error "scene file '$tmp/dx_inf.vtp': field data 'dx' holds inf; give a finite number" $short -scene_file "$tmp/dx_inf.vtp"
expect_error "the scene's field data t_end must be positive \(or pass -t_end\) \(got -1\)" ${short/-t_end 0.02/} -scene_file "$tmp/t_end_negative.vtp"
expect_ok $short -scene_file "$tmp/t_end_negative.vtp" -output_dir "$tmp/t_end_given"  # the option overrides the file
# A free_slip array: 1 on free-slip wall particles, else 0; never on fluid.
for d in free_slip_fluid free_slip_2; do damage $d; done
expect_error "scene file '$tmp/free_slip_fluid.vtp': particle [0-9]+ is fluid with free_slip 1; only wall particles have a slip condition" $short -scene_file "$tmp/free_slip_fluid.vtp"
expect_error "scene file '$tmp/free_slip_2.vtp': particle [0-9]+ has free_slip 2; give 1 on free-slip wall particles, else 0" $short -scene_file "$tmp/free_slip_2.vtp"
# A .vtp scene's free-slip walls do what the YAML scene's do: a channel driven along them by g moves as
# a plug, its momentum M g t (cases/scenes/free_slip_channel.yaml, tests/test_walls.cpp).
PYTHONPATH="$src/scripts" /usr/bin/python3 - "$tmp/channel.vtp" <<'PY' || { echo "FAIL: writing the free-slip channel"; fail=1; }
import sys
from sph_scene.scene import Scene, FLUID, WALL
nx, layers = 20, 4
dx = 1.0 / nx
s = Scene(2)
for j in range(-layers, 10 + layers):  # fluid 0 <= y < 0.5, walls below and above
    for i in range(nx):
        wall = j < 0 or j >= 10
        s.add(((i + 0.5) * dx, (j + 0.5) * dx), WALL if wall else FLUID, free_slip=wall)
s.params = {"dx": dx, "box": [0.0, 1.0, -layers * dx, 0.5 + layers * dx], "periodic": [1, 0], "gravity": [1.0, 0.0],
            "nu": 0.1, "rho0": 1.0, "U": 1.0, "free_surface": 0, "t_end": 0.2}
s.write(sys.argv[1])
PY
expect_ok -case scene -scene_file "$tmp/channel.vtp" -solver wcsph -progress 0 -threads 1 -output_interval 0 -output_dir "$tmp/channel"
tail -1 "$tmp/channel/timeseries.csv" | /usr/bin/python3 -c "
import sys; t, m = (float(v) for v in sys.stdin.read().split(',')[1:5:3])
sys.exit(0 if abs(m / (0.5 * t) - 1) < 1e-3 else 1)" && echo "ok: a .vtp scene's free-slip walls leave the driven channel a plug" ||
  { echo "FAIL: a .vtp scene's free-slip channel: momentum is not M g t"; tail -1 "$tmp/channel/timeseries.csv"; fail=1; }
make_scene cavity --nx 8 --wall-layers 2 -o "$tmp/thin.vtp"
expect_error "scene file '$tmp/thin.vtp': the walls near \(.*\) are 2 dx thick, thinner than the kernel support \(3 dx\); add wall layers" $short -scene_file "$tmp/thin.vtp"
# The kernel decides: the same walls are thick enough for a smaller support.
expect_ok $short -scene_file "$tmp/thin.vtp" -h_over_dx 1 -output_dir "$tmp/thin_ok"
expect_error "holds 2D points \(all z equal\), not 3D; drop -dim" $short -scene_file "$tmp/cavity.vtp" -dim 3
expect_error "-scene_periodic must list axes of this 2D scene" $short -scene_file "$tmp/cavity.vtp" -scene_periodic z
expect_error "-scene_box needs 4 values" $short -scene_file "$tmp/cavity.vtp" -scene_box 0,1,0
[ -e "$tmp/refused" ] && { echo "FAIL: a refused scene created its output directory"; fail=1; }

# Options override the file; a missing dx can come from the command line.
expect_ok $short -scene_file "$tmp/no_dx.vtp" -scene_dx 0.125 -nu 0.02 -output_dir "$tmp/override"
expect_json "$tmp/override/summary.json" "s['status'] == 'completed' and s['physics']['nu'] == 0.02 and s['dx'] == 0.125 and not s['parameters']['free_surface']" "override: -nu and -scene_dx taken, closed cavity has no free surface"
# A scene is identified by its content: the same file by another path restarts, another file of the
# same name does not.
mkdir -p "$tmp/moved"; cp "$tmp/cavity.vtp" "$tmp/moved/cavity.vtp"
expect_ok -case scene -scene_file "$tmp/cavity.vtp" -t_end 0.02 -progress 0 -threads 1 -output_dir "$tmp/first"
expect_ok -case scene -scene_file "$tmp/moved/cavity.vtp" -t_end 0.04 -progress 0 -threads 1 -restart "$tmp/first/checkpoint.bin" -output_dir "$tmp/moved_run"
make_scene cavity --nx 8 --re 50 -o "$tmp/moved/cavity.vtp"
expect_error "checkpoint .* was written with nu = 0.01, this run has nu = 0.02" -case scene -scene_file "$tmp/moved/cavity.vtp" -t_end 0.04 -progress 0 -threads 1 -restart "$tmp/first/checkpoint.bin" -output_dir "$tmp/refused"
# -help documents the scene's options.
"$sph" -help -case scene 2>&1 | grep -q -- "-scene_file" && echo "ok: -help lists -scene_file" || { echo "FAIL: -help lacks -scene_file"; fail=1; }

# Every scene of make-scene runs a few steps with both solvers; the 3D cavity too.
for scene in dam_break cylinders sloshing cavity; do
  make_scene $scene --nx 8 -o "$tmp/$scene.vtp"
  for solver in isph wcsph; do
    expect_ok -case scene -scene_file "$tmp/$scene.vtp" -solver $solver -max_steps 10 -progress 0 -threads 1 -output_dir "$tmp/$scene-$solver"
  done
done
expect_json "$tmp/dam_break-isph/summary.json" "s['parameters']['free_surface'] and s['parameters']['wall_thickness_dx'] == 4" "dam break: free surface detected, walls 4 dx"
make_scene cavity --dim 3 --nx 5 -o "$tmp/cavity3.vtp"
expect_ok -case scene -scene_file "$tmp/cavity3.vtp" -max_steps 5 -progress 0 -threads 1 -output_dir "$tmp/cavity3"
expect_json "$tmp/cavity3/summary.json" "s['dim'] == 3 and s['parameters']['moving_wall_particles'] > 0" "3D cavity: dimension from the points"

# Two ranks give the one-rank result (ISPH to the solver tolerance).
for n in 1 2; do
  "$mpiexec" -n $n "$sph" -case scene -scene_file "$tmp/dam_break.vtp" -t_end 0.2 -ppe_ksp_rtol 1e-10 -progress 0 \
    -output_interval 0 -output_dir "$tmp/mpi$n" >"$tmp/mpi$n.log" 2>&1 || { echo "FAIL: $n ranks:"; tail -3 "$tmp/mpi$n.log"; fail=1; }
done
/usr/bin/python3 - "$tmp/mpi1" "$tmp/mpi2" <<'PY' || fail=1
import glob, sys
import vtk
from vtk.util.numpy_support import vtk_to_numpy
def state(d):
    frames = sorted(glob.glob(d + "/particles_*.pvtp")) or sorted(glob.glob(d + "/particles_*.vtp"))
    r = vtk.vtkXMLPPolyDataReader() if frames[-1].endswith("pvtp") else vtk.vtkXMLPolyDataReader()
    r.SetFileName(frames[-1]); r.Update()
    o = r.GetOutput(); pd = o.GetPointData()
    order = vtk_to_numpy(pd.GetArray("id")).argsort()
    return vtk_to_numpy(o.GetPoints().GetData())[order]
a, b = state(sys.argv[1]), state(sys.argv[2])
diff = abs(a - b).max()
print(("ok" if diff < 1e-8 else "FAIL") + f": dam-break scene on 1 and 2 ranks, largest position difference {diff:.1e}")
sys.exit(0 if diff < 1e-8 else 1)
PY
exit $fail
