#!/usr/bin/env bash
# A scheme's own defaults, and how the options override them: WCSPH at a free surface runs the quintic
# spline at h = 0.93 dx (a support of 2.79 dx, where the symmetric force holds the square lattice) with
# the wall bounding; -kernel or -h_over_dx alone takes the general default for the other (a kernel and
# its h go together); elsewhere, and for ISPH, Wendland C2 at 3 dx.   usage: scheme_defaults.sh <sph> <src>
set -u
sph="$1"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
still="-case still_water -nx 10 -max_steps 1 -progress 0 -output_interval 0 -threads 1 -overwrite"

run() {  # run <name> <options...>: one step, then its summary.json is $tmp/<name>/summary.json
  local name="$1"; shift
  expect_ok "$@" -output_dir "$tmp/$name"
}
run wcsph_surface $still -solver wcsph
expect_json "$tmp/wcsph_surface/summary.json" \
  's["kernel"]["type"] == "quintic_spline" and abs(s["kernel"]["h_over_dx"] - 0.93) < 1e-12 and "bounding" in s["models"]["walls"]' \
  "WCSPH at a free surface: quintic spline at h = 0.93 dx, walls bounded"
run wcsph_kernel $still -solver wcsph -kernel wendland_c2
expect_json "$tmp/wcsph_kernel/summary.json" \
  's["kernel"]["type"] == "wendland_c2" and abs(s["kernel"]["h_over_dx"] - 1.5) < 1e-12' \
  "-kernel alone: that kernel at a support of 3 dx"
run wcsph_h $still -solver wcsph -h_over_dx 2
expect_json "$tmp/wcsph_h/summary.json" 's["kernel"]["type"] == "wendland_c2" and s["kernel"]["h_over_dx"] == 2' \
  "-h_over_dx alone: Wendland C2 at that h"
run wcsph_unbounded $still -solver wcsph -wall_bounding 0
expect_json "$tmp/wcsph_unbounded/summary.json" '"bounding" not in s["models"]["walls"]' "-wall_bounding 0 switches it off"
run isph_surface $still -solver isph
expect_json "$tmp/isph_surface/summary.json" 's["kernel"]["type"] == "wendland_c2" and s["kernel"]["h_over_dx"] == 1.5' \
  "ISPH at a free surface: Wendland C2 at 3 dx"
run wcsph_closed -case taylor_green -nx 8 -max_steps 1 -progress 0 -output_interval 0 -overwrite -solver wcsph
expect_json "$tmp/wcsph_closed/summary.json" \
  's["kernel"]["type"] == "wendland_c2" and s["kernel"]["h_over_dx"] == 1.5 and "walls" not in s["models"]' \
  "WCSPH without a free surface: Wendland C2 at 3 dx"
exit $fail
