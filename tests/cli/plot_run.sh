#!/usr/bin/env bash
# scripts/plot-run: a run with a body (the baffle, nx 12) and one on 2 ranks (.pvtp frames) each give a
# PNG holding the frame and the force histories; the body's surface file carries the pressure, shear
# and traction its force was taken with; the frame nearest --time is taken; a field or a column
# the run lacks, or a folder that is no run, gives one error line naming what exists, exit non-zero.
#   usage: plot_run.sh <sph executable> <source dir>; $MPIEXEC names mpiexec.
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mpiexec="${MPIEXEC:-mpiexec}"
fail=0
pr="$src/scripts/plot-run"
bad() { echo "FAIL: $*"; fail=1; }
ok() { echo "ok: $*"; }

args=(-case scene -scene_file "$src/cases/scenes/baffle_sloshing.yaml" -nx 12 -t_end 0.1 -output_interval 0.05
      -threads 1 -progress 0)
"$sph" "${args[@]}" -output_dir "$tmp/one" >"$tmp/one.log" 2>&1 || { bad "sph run exited non-zero"; cat "$tmp/one.log"; }
"$mpiexec" -n 2 "$sph" "${args[@]}" -output_dir "$tmp/two" >"$tmp/two.log" 2>&1 ||
  { bad "2-rank run exited non-zero"; cat "$tmp/two.log"; }

for run in one two; do
  out=$("$pr" "$tmp/$run" -o "$tmp/$run.png" 2>&1)
  # A PNG starts with its 8-byte signature; the figure is two panels, so it is wide.
  if [ -s "$tmp/$run.png" ] && [ "$(head -c 8 "$tmp/$run.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; then
    ok "plot-run $run: $out"
  else
    bad "plot-run $run wrote no PNG: $out"
  fi
done
out=$("$pr" "$tmp/one" --time 0.04 --field speed --columns force_baffle_x -o "$tmp/t.png" 2>&1)
# Three frames: at 0, near 0.05 (the first step past it) and at 0.1; 0.04 is nearest the middle one.
t=$(echo "$out" | sed -n 's/.*frame at t = \([0-9.e-]*\)).*/\1/p')
[ -s "$tmp/t.png" ] && python3 -c "import sys; sys.exit(not 0.04 < float('$t') < 0.07)" 2>/dev/null &&
  ok "--time 0.04 --field speed --columns force_baffle_x: $out" || bad "--time 0.04: $out"

# The surface files carry each face's pressure, shear and traction from the step's state: the
# pressure's traction integrates to the force_baffle_pressure column at that time, the shear to the
# force_baffle_viscous one; the first frame, before any step, carries none.
/usr/bin/python3 - "$tmp/one" <<'PY' && ok "the baffle's surface loads sum to its pressure and viscous forces" || bad "surface loads"
import csv, sys
import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy as n
run = sys.argv[1]
def read(k):
    r = vtk.vtkXMLPolyDataReader(); r.SetFileName(f"{run}/body_baffle_{k:05d}.vtp"); r.Update(); return r.GetOutput()
o = read(2)
pts, lines = n(o.GetPoints().GetData()), o.GetLines()
ids, off = n(lines.GetConnectivityArray()), n(lines.GetOffsetsArray())
# The traction is the pressure's, -p n, plus the viscous shear, which each face carries apart.
traction = n(o.GetCellData().GetArray("traction")) - n(o.GetCellData().GetArray("shear"))
F = sum(traction[c] * np.linalg.norm(pts[ids[b - 1]] - pts[ids[a]]) for c, (a, b) in enumerate(zip(off[:-1], off[1:])))
shear = n(o.GetCellData().GetArray("shear"))
S = sum(shear[c] * np.linalg.norm(pts[ids[b - 1]] - pts[ids[a]]) for c, (a, b) in enumerate(zip(off[:-1], off[1:])))
row = list(csv.DictReader(open(f"{run}/timeseries.csv")))[-1]
want = np.array([float(row["force_baffle_pressure_x"]), float(row["force_baffle_pressure_y"])])
viscous = np.array([float(row["force_baffle_viscous_x"]), float(row["force_baffle_viscous_y"])])
print(f"surface {F[:2]}, force columns {want}; shear {S[:2]}, viscous columns {viscous}")
sys.exit(not (abs(F[:2] - want).max() <= 1e-9 * abs(want).max() and abs(want).max() > 0
              and abs(S[:2] - viscous).max() <= 1e-9 * abs(viscous).max() and abs(viscous).max() > 0
              and read(0).GetCellData().GetNumberOfArrays() == 0))
PY

expect_error() {  # expect_error <what the message must name> <args...>
  local want="$1"; shift
  local out; out=$("$pr" "$@" -o "$tmp/x.png" 2>&1) && { bad "plot-run $* succeeded"; return; }
  [ "$(echo "$out" | wc -l)" -eq 1 ] && echo "$out" | grep -q -- "$want" && ok "refused: $out" ||
    bad "plot-run $*: wanted one line naming '$want', got: $out"
}
expect_error "choose one of speed, pressure" "$tmp/one" --field nope
expect_error "has no column force_nope; it has step" "$tmp/one" --columns force_nope
expect_error "is not a folder" "$tmp/missing"
mkdir "$tmp/empty"
expect_error "has no particles.pvd" "$tmp/empty"
exit $fail
