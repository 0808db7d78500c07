#!/usr/bin/env bash
# Inlets and outlets (src/boundary/open_boundaries.hpp) on plane Poiseuille flow between an inlet that
# brings the exact profile and an outlet at zero pressure (cases/scenes/poiseuille_channel.yaml), both
# schemes: the steady profile and pressure gradient against the exact solution, the fluid's mass its
# start's plus what came in less what went out (to round-off), a restart that equals the uninterrupted
# run bit for bit while particles come and go, 2 threads against 1 (bitwise) and 2 ranks against 1, and
# the refusals of what is not built or makes no open boundary.   usage: open_boundaries.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mpiexec="${MPIEXEC:-mpiexec}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
fail=0
source "$(dirname "$0")/lib/expect.sh"
scene="$src/cases/scenes/poiseuille_channel.yaml"
quick="-case scene -scene_file $scene -nx 20 -progress 0 -threads 1"
for s in isph wcsph; do
  expect_ok $quick -solver $s -output_interval 0.25 -output_dir "$tmp/$s"
done
# Stopped mid-run (particles have come and gone) and continued, on the same step sequence; WCSPH's
# transmissive outlet carries its pressures and last mean velocity through the checkpoint.
expect_ok $quick -solver isph -t_end 3 -output_interval 3 -max_steps 200 -output_dir "$tmp/half"
expect_ok $quick -solver isph -t_end 3 -output_interval 3 -restart "$tmp/half/checkpoint.bin" -output_dir "$tmp/resumed"
expect_ok $quick -solver isph -t_end 3 -output_interval 3 -output_dir "$tmp/isph1"
expect_ok $quick -solver isph -t_end 3 -output_interval 3 -output_dir "$tmp/threads2" -threads 2
expect_ok $quick -solver wcsph -t_end 3 -output_interval 3 -max_steps 1000 -output_dir "$tmp/whalf"
expect_ok $quick -solver wcsph -t_end 3 -output_interval 3 -restart "$tmp/whalf/checkpoint.bin" -output_dir "$tmp/wresumed"
expect_ok $quick -solver wcsph -t_end 3 -output_interval 3 -output_dir "$tmp/wcsph1"
for s in isph wcsph; do
  "$mpiexec" -n 2 "$sph" $quick -solver $s -t_end 3 -output_interval 3 -output_dir "$tmp/${s}2" >"$tmp/${s}2.log" 2>&1 ||
    { echo "FAIL: $s on 2 ranks"; tail -3 "$tmp/${s}2.log"; fail=1; }
done

PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp" "$src" <<'PY' || fail=1
import csv, json, subprocess, sys
tmp, src = sys.argv[1:3]
from checks import check, finish
def figures(run):
    out = subprocess.run([f"{src}/scripts/poiseuille-check", f"{tmp}/{run}", "--window", "2"], capture_output=True,
                         text=True)
    return json.loads(out.stdout) if out.returncode == 0 else None
# Bounds at nx 20, t = 4 to 6, from docs/verification/open_boundaries.md (there: ISPH's velocity error
# 0.64 %, its pressure gradient -2.5 %; WCSPH's 0.6 % and +1.7 %). The flow is steady: frame to frame
# the fitted gradient moves by 3 % of it in WCSPH (10 % with a fixed-pressure outlet, which reflects
# sound back into the channel).
bounds = {"isph": (0.01, 0.05), "wcsph": (0.01, 0.05)}
for run, solver in (("isph", "isph"), ("wcsph", "wcsph")):
    f = figures(run)
    if f is None:
        check(False, f"{run}: poiseuille-check"); continue
    l2, grad = bounds[solver]
    check(f["velocity_l2"] < l2, f"{run}: velocity profile's relative L2 error {f['velocity_l2']:.2e} < {l2}")
    check(abs(f["pressure_gradient_error"]) < grad,
          f"{run}: pressure gradient {f['pressure_gradient']:.4f} within {grad:.0%} of -0.8")
    check(f["pressure_gradient_std"] < 0.05 * 0.8, f"{run}: the gradient moves frame to frame by "
          f"{f['pressure_gradient_std']:.4f} < 5 % of it")
    check(f["inflow_mass"] > 1.5 and f["outflow_mass"] > 1.0, f"{run}: fluid came in ({f['inflow_mass']:.3f}) and went out "
          f"({f['outflow_mass']:.3f})")
    check(abs(f["mass_balance"]) < 1e-12, f"{run}: the fluid's mass is its start's plus in less out "
          f"(off by {f['mass_balance']:.1e})")
last = lambda run: list(csv.DictReader(open(f"{tmp}/{run}/timeseries.csv")))[-1]
a, b = last("isph1"), last("resumed")
check(a == b, "the restart's last row equals the uninterrupted run's, every column bitwise")
check(last("wcsph1") == last("wresumed"), "WCSPH: the restart's last row equals the uninterrupted run's, bitwise")
check(a == last("threads2"), "2 threads: the last row equals 1 thread's, every column bitwise")
s = json.load(open(f"{tmp}/isph/summary.json"))
check(s["n_particles_final"] != s["n_particles"] or s["conservation"]["open_boundaries"]["inflow"]["particles"] > 0,
      "summary.json counts the particles that came in and went out")
for s in ("isph", "wcsph"):
    f1, f2 = figures(f"{s}1"), figures(f"{s}2")
    check(f1 is not None and f2 is not None, f"{s}: poiseuille-check reads the 1- and 2-rank runs")
    if f1 and f2:
        check(abs(f1["pressure_gradient"] / f2["pressure_gradient"] - 1) < 1e-6, f"{s} on 2 ranks: pressure "
              f"gradient {f2['pressure_gradient']:.10f} against 1 rank's {f1['pressure_gradient']:.10f}")
        check(abs(f2["mass_balance"]) < 1e-12,
              f"{s} on 2 ranks: the fluid's mass balance holds (off by {f2['mass_balance']:.1e})")
finish()
PY

# A speed table doubles the inflow at t = 0.5 to 0.6 (no ramp): the rate at which mass comes in (a
# least-squares slope of inflow_mass over each stretch; particles cross a row at a time, so the count
# itself is a staircase, up to a particle per row off) is rho times the parabola's flux, 2/3 U_max H,
# times the factor, to 2.5 %.
sed 's/ramp: 0.5}/speed_table: speed.csv}/' "$scene" > "$tmp/table.yaml"
printf 't,factor\n0,1\n0.5,1\n0.6,2\n' > "$tmp/speed.csv"
for s in isph wcsph; do
  expect_ok -case scene -scene_file "$tmp/table.yaml" -nx 20 -progress 0 -threads 1 -t_end 1 -output_interval 0 \
    -solver $s -output_dir "$tmp/table-$s"
done
PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp" <<'PY' || fail=1
import csv, sys
from checks import check, finish
for s in ("isph", "wcsph"):
    rows = list(csv.DictReader(open(f"{sys.argv[1]}/table-{s}/timeseries.csv")))
    for a, b, factor in ((0.1, 0.5, 1), (0.6, 1.0, 2)):
        pts = [(float(r["t"]), float(r["inflow_mass"])) for r in rows if a <= float(r["t"]) <= b]
        mt, mm = (sum(p[k] for p in pts) / len(pts) for k in (0, 1))
        rate = sum((t - mt) * (m - mm) for t, m in pts) / sum((t - mt) ** 2 for t, m in pts)
        want = factor * 2 / 3
        check(abs(rate / want - 1) < 0.025,
              f"{s}: inflow rate over [{a}, {b}] {rate:.4f}, factor {factor} gives {want:.4f}")
finish()
PY

# Velocity profiles as expressions: the parabola written out gives the parabolic inlet's run to round-off
# (the same reference speed U, taken from the expressions' largest speed across the section); a flatter
# profile, u = 1.5 (1 - (2y - 1)^4), brings in its own flux, rho 1.5 (1 - 1/5) = 1.2, to 2.5 %.
sed 's/velocity: {parabolic: 1}/velocity: {expression: ["4 * y * (1 - y)", "0"]}/' "$scene" > "$tmp/parabola.yaml"
sed 's/velocity: {parabolic: 1}/velocity: {expression: ["1.5 * (1 - (2*y - 1)^4)", "0"]}/' "$scene" > "$tmp/flat.yaml"
for f in parabola flat; do
  expect_ok -case scene -scene_file "$tmp/$f.yaml" -nx 20 -progress 0 -threads 1 -t_end 1 -output_interval 0 \
    -solver isph -output_dir "$tmp/expr-$f"
done
expect_ok $quick -solver isph -t_end 1 -output_interval 0 -output_dir "$tmp/expr-parabolic"
PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp" <<'PY' || fail=1
import csv, json, sys
from checks import check, finish
tmp = sys.argv[1]
rows = {r: list(csv.DictReader(open(f"{tmp}/expr-{r}/timeseries.csv"))) for r in ("parabola", "parabolic", "flat")}
a, b = rows["parabola"][-1], rows["parabolic"][-1]
check(json.load(open(f"{tmp}/expr-parabola/summary.json"))["parameters"]["U"] == 1.0,
      "the parabola's expression sets U = 1, its peak, as the parabolic inlet does")
for col in ("kinetic_energy", "momentum_x", "inflow_mass", "outflow_mass", "fluid_mass"):
    check(abs(float(a[col]) - float(b[col])) <= 1e-12 * max(1.0, abs(float(b[col]))),
          f"the parabola as an expression: {col} {a[col]} against the parabolic inlet's {b[col]}")
pts = [(float(r["t"]), float(r["inflow_mass"])) for r in rows["flat"] if 0.6 <= float(r["t"]) <= 1.0]
mt, mm = (sum(p[k] for p in pts) / len(pts) for k in (0, 1))
rate = sum((t - mt) * (m - mm) for t, m in pts) / sum((t - mt) ** 2 for t, m in pts)
check(abs(rate / 1.2 - 1) < 0.025, f"the flat profile's inflow rate over [0.6, 1] {rate:.4f} against its flux 1.2")
finish()
PY

# A lake at rest beside an outlet that keeps its level: the buffer's hydrostatic pressure holds the
# water as a wall would, both schemes. Nothing crosses the outlet's plane and the fluid stays at rest:
# its RMS speed under 1 % of the long waves' speed sqrt(g h) (the figures: docs/verification/open_boundaries.md).
cat > "$tmp/lake.yaml" <<'YAML'
dimension: 2
box: [-0.2, 2, -0.2, 1.0]
gravity: [0, -9.81]
nu: 1.0e-6
rho0: 1000
free_surface: true
t_end: 3
regions:
  - {role: wall, shape: difference, of: [{box: [-0.2, 3, -0.2, 1.0]}, {box: [0, 3, 0, 1.2]}]}
  - {role: fluid, shape: box, bounds: [0, 2, 0, 0.5], pressure: hydrostatic}
  - {role: outlet, side: x+, level: 0.5}
YAML
for s in isph wcsph; do
  expect_ok -case scene -scene_file "$tmp/lake.yaml" -nx 20 -progress 0 -threads 1 -output_interval 0 -solver $s \
    -output_dir "$tmp/lake-$s"
done
PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp" <<'PY' || fail=1
import csv, math, sys
from checks import check, finish
tmp = sys.argv[1]
for s in ("isph", "wcsph"):
    rows = list(csv.DictReader(open(f"{tmp}/lake-{s}/timeseries.csv")))
    first, last = rows[0], rows[-1]
    mass = float(last["fluid_mass"])
    check(float(last["outflow_mass"]) == 0.0 and mass == float(first["fluid_mass"]),
          f"{s}: the lake keeps its water (fluid mass {mass}, out {last['outflow_mass']})")
    rms = math.sqrt(2 * float(last["kinetic_energy"]) / mass)
    bound = 0.01 * math.sqrt(9.81 * 0.5)
    check(rms < bound, f"{s}: the lake stays at rest: RMS speed {rms:.2e} < {bound:.3f} m/s")
finish()
PY

# An open channel over a bump (cases/scenes/bump_channel.yaml), ISPH nx 20 to t = 8: the particles keep
# their volume along the through-flow (-ppe_density_relaxation, on by default with open boundaries), so
# a metre past the bump their number density is a lattice's and the surfaces by the fluid's volume and
# by its top particles agree (without it they spread apart; docs/verification/open_boundaries.md).
expect_ok -case scene -scene_file "$src/cases/scenes/bump_channel.yaml" -nx 20 -t_end 8 -output_interval 0.5 \
  -progress 0 -threads 1 -solver isph -output_dir "$tmp/bump"
"$src/scripts/bump-check" "$tmp/bump" --window 2 > "$tmp/bump.json" || { echo "FAIL: bump-check"; fail=1; }
PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp" <<'PY' || fail=1
import csv, json, sys
from checks import check, finish
tmp = sys.argv[1]
f = json.load(open(f"{tmp}/bump.json"))
check(abs(f["number_density_downstream"] - 1) < 0.02,
      f"the channel's particles keep their volume: number density downstream {f['number_density_downstream']:.4f}")
gap = abs(f["downstream_surface"] - f["top_downstream"])
check(gap < 0.01, f"its surface by volume and by top particles agree downstream: "
      f"{f['downstream_surface']:.4f}, {f['top_downstream']:.4f}")
check(abs(f["flow_rate"] / 0.45 - 1) < 0.03, f"it carries the inlet's flow rate: {f['flow_rate']:.4f} (0.45)")
rows = list(csv.DictReader(open(f"{tmp}/bump/timeseries.csv")))
first, last = rows[0], rows[-1]
balance = float(last["fluid_mass"]) - float(first["fluid_mass"]) - float(last["inflow_mass"]) + float(last["outflow_mass"])
removed = float(last["removed_fluid"]) if "removed_fluid" in last else 0.0
check(abs(balance) < 1e-9 * float(first["fluid_mass"]) + removed * 2.5 + 1e-12,
      f"its fluid's mass is its start's plus in less out (off by {balance:.2e}, {removed:.0f} removed)")
finish()
PY

# What is not built, or makes no open boundary, is refused in one line.
bad() { sed "$1" "$scene" > "$tmp/bad.yaml"; }
bad 's/velocity: {parabolic: 1}/velocity: [-1, 0]/'
expect_error "velocity.*points out of the box .*must point into the box" -case scene -scene_file "$tmp/bad.yaml" -nx 10 -output_dir "$tmp/b1"
bad 's/side: x+, pressure: 0/side: q+/'
expect_error "side.*is not a side of the box; give one of x-, x\+, y- or y\+" -case scene -scene_file "$tmp/bad.yaml" -nx 10 -output_dir "$tmp/b2"
bad 's/side: x+, pressure: 0/side: x-/'
expect_error "side x- a second time" -case scene -scene_file "$tmp/bad.yaml" -nx 10 -output_dir "$tmp/b3"
bad 's/side: x+, pressure: 0/side: y+/'
expect_error "where no fluid region meets the box's side" -case scene -scene_file "$tmp/bad.yaml" -nx 10 -output_dir "$tmp/b4"
bad 's/velocity: {parabolic: 1}/velocity: {expression: ["y - 0.5", "0"]}/'
expect_error "velocity.expression: points out of the box at \(-?0.025, 0.025\) \(x component -0.475\)" -case scene -scene_file "$tmp/bad.yaml" -nx 20 -output_dir "$tmp/b7"
bad 's/velocity: {parabolic: 1}/velocity: {expression: ["4 * y * (1 - q)", "0"]}/'
expect_error "velocity.expression\[0\]: '4 \* y \* \(1 - q\)' is not an expression of x, y: .*q" -case scene -scene_file "$tmp/bad.yaml" -nx 10 -output_dir "$tmp/b8"
bad 's/velocity: {parabolic: 1}/velocity: {expression: ["1"]}/'
expect_error "velocity.expression: must list two expressions, \[u, v\], one a velocity component, of x and y" -case scene -scene_file "$tmp/bad.yaml" -nx 10 -output_dir "$tmp/b9"
bad 's|velocity: {parabolic: 1}|velocity: {expression: ["sqrt(y - 0.5)", "0"]}|'
expect_error "velocity.expression: is not a finite number at \(0.025, 0.025\)" -case scene -scene_file "$tmp/bad.yaml" -nx 20 -output_dir "$tmp/b6"
expect_error "an outlet in a free-surface scene needs the water level it keeps .*add level: H to the outlet" -case scene \
  -scene_file "$scene" -nx 10 -free_surface 1 -output_dir "$tmp/b5"
bad 's/side: x+, pressure: 0/side: x+, level: 0.5/'
expect_error "regions\[4\].level: keeps a water level, and the scene has no gravity; add gravity" -case scene \
  -scene_file "$tmp/bad.yaml" -nx 10 -output_dir "$tmp/b10"
exit $fail
