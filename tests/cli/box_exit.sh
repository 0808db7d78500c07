#!/usr/bin/env bash
# -box_exit: fluid that leaves the box through a side that is not periodic and that no wall covers is
# taken out of the run and counted by default (auto), with a warning line; with -box_exit stop it stops
# the run, with the particle named and the option that lets it go; -box_exit remove takes out whatever
# leaves. (Which crossings went through a wall: tests/test_box_exit.cpp.) Mass is conserved exactly: the fluid left plus the fluid removed is the fluid at the
# start, on 1 and 2 ranks, and across a restart.   usage: box_exit.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mpiexec="${MPIEXEC:-mpiexec}"
fail=0
source "$(dirname "$0")/lib/expect.sh"
# A block of water 0.8 wide on a pedestal 0.5 wide: both ends fall off and out of the box's floor.
cat > "$tmp/ledge.yaml" <<'YAML'
dimension: 2
box: [-0.3, 1.3, -0.4, 1.0]
gravity: [0, -1]
nu: 0.01
rho0: 1
free_surface: true
regions:
  - {role: wall, shape: box, bounds: [0.25, 0.75, 0, 0.2]}
  - {role: fluid, shape: box, bounds: [0.1, 0.9, 0.2, 0.6]}
YAML
quick="-case scene -scene_file $tmp/ledge.yaml -nx 20 -t_end 1.5 -progress 0 -threads 1 -output_interval 0.3"
for s in isph wcsph; do
  expect_error "fluid particle [0-9]+ near .* left the box .*-box_exit auto or remove" $quick -solver $s -box_exit stop \
    -output_dir "$tmp/$s-stop"
  expect_ok $quick -solver $s -box_exit remove -output_dir "$tmp/$s"
  expect_ok $quick -solver $s -output_dir "$tmp/$s-auto"
  grep -qE "^sph: warning: step [0-9]+ .* fluid particles? left the box over an open side and w.* taken out of the run" \
    "$tmp/stderr" && echo "ok: $s: the removal is said" || { echo "FAIL: $s: no removal warning"; cat "$tmp/stderr"; fail=1; }
done
# A slab only 3 particles deep thins into sheets as it spills. With the walls' old impact term instead
# of the bounding, ISPH's run stops on the neighbour count with the advice measured for a splash (a
# finer -nx completes it, a smaller -cfl fails sooner); with the bounding (the default) it completes.
sed 's/bounds: \[0.1, 0.9, 0.2, 0.6\]/bounds: [0.1, 0.9, 0.2, 0.35]/; s/bounds: \[0.25, 0.75, 0, 0.2\]/bounds: [0.3, 0.7, 0, 0.2]/' \
  "$tmp/ledge.yaml" > "$tmp/slab.yaml"
slab="-case scene -scene_file $tmp/slab.yaml -nx 20 -t_end 1.6 -progress 0 -threads 1 -output_interval 0.4 -solver isph -box_exit remove"
expect_error "neighbour count collapsed: .* sheets and drops thinner than the kernel support.* a finer -nx" \
  $slab -ppe_wall_impact 1 -wall_bounding 0 -output_dir "$tmp/slab"
expect_ok $slab -output_dir "$tmp/slab-bounded"
OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 \
  "$mpiexec" -n 2 "$sph" $quick -solver wcsph -box_exit remove -output_dir "$tmp/wcsph2" >/dev/null 2>&1 ||
  { echo "FAIL: 2 ranks"; fail=1; }
# A restart from the checkpoint at t = 1.2, after the first particles went (t ~ 1.13), carries the
# count on and takes them out again.
expect_ok $quick -solver wcsph -box_exit remove -t_end 1.2 -output_dir "$tmp/half"
expect_ok $quick -solver wcsph -box_exit remove -restart "$tmp/half/checkpoint.bin" -output_dir "$tmp/resumed"

PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp" <<'PY' || fail=1
import csv, json, sys
tmp = sys.argv[1]
from checks import check, finish
start = 0.8 * 0.4 * 1.0  # the block's mass: rho0 times its area (16 x 8 particles of 0.05^2 at nx 20)
for run in ("isph", "wcsph", "isph-auto", "wcsph-auto", "wcsph2", "resumed"):
    s = json.load(open(f"{tmp}/{run}/summary.json"))
    c = s["conservation"]
    rows = list(csv.DictReader(open(f"{tmp}/{run}/timeseries.csv")))
    counts = [float(r["removed_fluid"]) for r in rows]
    gone = c["removed_fluid"]
    check(gone["particles"] > 0 and counts[-1] == gone["particles"] and counts == sorted(counts),
          f"{run}: {gone['particles']} particles removed, the count never falling")
    check(abs(c["fluid_mass"] + gone["mass"] - start) < 1e-12,
          f"{run}: fluid left {c['fluid_mass']:.6f} + removed {gone['mass']:.6f} = the start's {start:.6f}")
    check(gone["particles"] < 128, f"{run}: the fluid on the pedestal stays ({128 - gone['particles']} particles)")
one = json.load(open(f"{tmp}/wcsph/summary.json"))["conservation"]["removed_fluid"]
# Over the box's open floor, far from any wall: auto takes out what remove does, bit for bit.
for s in ("isph", "wcsph"):
    check(open(f"{tmp}/{s}-auto/timeseries.csv").read() == open(f"{tmp}/{s}/timeseries.csv").read(),
          f"{s}: auto's run is remove's")
# Resumed: the same particles taken out (the first run's step lands on t = 1.2 and the uninterrupted
# one's does not, so the sum of their masses may differ at round-off). On 2 ranks WCSPH's round-off grows (tests/cli/mpi.sh): a particle
# may cross the box's floor a step apart, not more than one or two.
half = json.load(open(f"{tmp}/half/summary.json"))["conservation"]["removed_fluid"]
check(half["particles"] > 0, f"the checkpoint at t = 1.2 holds {half['particles']} removed particles")
resumed = json.load(open(f"{tmp}/resumed/summary.json"))["conservation"]["removed_fluid"]
check(resumed["particles"] == one["particles"] and abs(resumed["mass"] - one["mass"]) < 1e-14,
      f"resumed: removed {resumed['particles']}, as one uninterrupted run ({one['particles']})")
two = json.load(open(f"{tmp}/wcsph2/summary.json"))["conservation"]["removed_fluid"]
check(abs(two["particles"] - one["particles"]) <= 2, f"2 ranks removed {two['particles']}, one rank {one['particles']}")
finish()
PY
exit $fail
