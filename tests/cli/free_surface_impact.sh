#!/usr/bin/env bash
# A block of water falling onto a cylinder above a pool (scripts/make-scene falling_block), at 20
# particles a unit, through its first impacts (on the cylinder at t ~ 0.6, into the pool at t ~ 1),
# with both schemes: the run completes, no fluid particle is ever inside a wall (timeseries.csv's
# fluid_in_walls), the surface share is recorded, and the fluid's energy (kinetic plus potential, from
# the frames) never exceeds its start: viscosity and impacts only take energy away.
#   usage: free_surface_impact.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
"$src/scripts/make-scene" falling_block --nx 20 -o "$tmp/block.vtp" >/dev/null || { echo "FAIL: make-scene"; exit 1; }
for solver in isph wcsph; do
  if ! "$sph" -case scene -scene_file "$tmp/block.vtp" -solver $solver -t_end 1.2 -output_interval 0.1 -threads 1 \
      -progress 0 -output_dir "$tmp/$solver" >"$tmp/$solver.log" 2>&1; then
    echo "FAIL: $solver exited non-zero:"; tail -3 "$tmp/$solver.log"; fail=1; continue
  fi
  /usr/bin/python3 - "$tmp/$solver" <<'PY' || fail=1
import csv, glob, json, sys
import vtk
from vtk.util.numpy_support import vtk_to_numpy
run = sys.argv[1]
s = json.load(open(run + "/summary.json"))
rows = list(csv.DictReader(open(run + "/timeseries.csv")))
inside = max(float(r["fluid_in_walls"]) for r in rows)
share = [float(r["free_surface_share"]) for r in rows]
energies = []
for f in sorted(glob.glob(run + "/particles_[0-9]*.vtp")):
    r = vtk.vtkXMLPolyDataReader(); r.SetFileName(f); r.Update(); o = r.GetOutput(); pd = o.GetPointData()
    x = vtk_to_numpy(o.GetPoints().GetData()); kind = vtk_to_numpy(pd.GetArray("kind"))
    m = vtk_to_numpy(pd.GetArray("mass")); v = vtk_to_numpy(pd.GetArray("velocity"))
    fl = kind == 0
    energies.append(float((0.5 * m[fl] * (v[fl] ** 2).sum(axis=1) + m[fl] * 1.0 * x[fl, 1]).sum()))
e0, released = energies[0], energies[0] - min(energies)
ok = s["status"] == "completed" and inside == 0 and 0 < min(share) and max(share) < 1 and max(energies) <= e0 * (1 + 1e-12)
print(("ok" if ok else "FAIL") + f": {s['solver']}: completed to t = {s['t_final']:.2f}, fluid in walls at most {inside:.0f}, "
      f"surface share {min(share):.2f}-{max(share):.2f}, energy at most {max(energies) / e0:.6f} of its start "
      f"({released / e0:.3f} of it released)")
sys.exit(0 if ok else 1)
PY
done
exit $fail
