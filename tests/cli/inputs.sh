#!/usr/bin/env bash
# Input refused at the start, naming the option and the fix, before anything is written; a forced
# -dt runs with its warning kept in summary.json; a checkpoint write that fails (full disk, injected)
# is named, leaves a summary and no temporary file.   usage: inputs.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
small="-case taylor_green -nx 8 -t_end 0.02 -progress 0"
expect_error "-output_interval must be -1 .* or positive \(got -2\)" $small -output_interval -2 -output_dir "$tmp/a"
expect_error "-checkpoint_interval must be -1 .* \(got -5\)" $small -checkpoint_interval -5 -output_dir "$tmp/a"
expect_error "-steady_tol must be -1 .* \(got -3\)" $small -steady_tol -3 -output_dir "$tmp/a"
expect_error "-wcsph_pressure_gradient corrected needs a scene without a free surface" -case still_water -solver wcsph -nx 8 -wcsph_pressure_gradient corrected -progress 0 -output_dir "$tmp/pgc"
expect_error "-density summation needs a scene without a free surface.*use -density continuity" -case still_water -solver wcsph -nx 8 -density summation -progress 0 -output_dir "$tmp/dsum"
expect_error "-max_steps must be -1 .* \(got -4\)" $small -max_steps -4 -output_dir "$tmp/a"
expect_error "-ppe_pc_drop_tol must be in \[0, 1\) \(got 1.5\)" $small -ppe_pc_drop_tol 1.5 -output_dir "$tmp/a"
expect_error "raise -c0 so that c0 > " -case taylor_green -solver wcsph -c0 0.01 -nx 8 -t_end 0.02 -progress 0 -output_dir "$tmp/a"
expect_error "-density_diffusion particle needs a scene without walls or a free surface.*use -density_diffusion molteni" -case lid_driven_cavity -solver wcsph -density_diffusion particle -nx 10 -t_end 0.02 -progress 0 -output_dir "$tmp/a"
expect_error "-prepared_start needs a case that gives its start.s slow-manifold velocity.*remove the option" -case lid_driven_cavity -solver wcsph -prepared_start -nx 10 -t_end 0.02 -progress 0 -output_dir "$tmp/a"
expect_error "-dt 0.1 exceeds the scheme's stability limit .*-dt_force 1" $small -dt 0.1 -output_dir "$tmp/a"
[ -e "$tmp/a" ] && { echo "FAIL: a refused run created its output directory"; fail=1; }
expect_ok $small -t_end 0.1 -dt 0.05 -dt_force 1 -output_dir "$tmp/forced"
expect_json "$tmp/forced/summary.json" "s['status'] == 'completed' and 'stability limit' in s['warnings'][0]" "forced -dt: warning in summary.json"

# The second checkpoint write fails as on a full disk.
SPH_FAULT_CHECKPOINT=full:2 "$sph" $small -t_end 0.05 -checkpoint_interval 0.01 -output_dir "$tmp/full" 2>"$tmp/err"
rc=$?
if [ $rc -ne 0 ] && [ "$(grep -c . "$tmp/err")" -eq 1 ] && grep -q "writing checkpoint .*checkpoint.bin failed: No space left" "$tmp/err"
then echo "ok: full disk -> $(cat "$tmp/err")"; else echo "FAIL: full disk -> rc=$rc:"; cat "$tmp/err"; fail=1; fi
expect_json "$tmp/full/summary.json" "s['status'] == 'failed' and 'writing checkpoint' in s['failure']" "full disk: failed summary names the checkpoint"
[ ! -e "$tmp/full/checkpoint.bin.tmp" ] && [ -s "$tmp/full/checkpoint.bin" ] || { echo "FAIL: full disk: .tmp left or the first checkpoint lost"; fail=1; }
# A disk that is really full (a 64 kB file system in a private mount namespace, where the system lets a
# test make one): PETSc's writer names only byte counts; the message says the disk is full.
mkdir -p "$tmp/tiny_fs"
if unshare -rm sh -c 'mount -t tmpfs -o size=64k tmpfs "$1"' _ "$tmp/tiny_fs" 2>/dev/null; then
  unshare -rm bash -c 'mount -t tmpfs -o size=64k tmpfs "$1" && "$2" -case dam_break -nx 20 -t_end 0.3 \
    -checkpoint_interval 0.05 -output_interval 0 -progress 0 -output_dir "$1/run"' _ "$tmp/tiny_fs" "$sph" 2>"$tmp/err"
  rc=$?
  if [ $rc -eq 1 ] && [ "$(grep -c . "$tmp/err")" -eq 1 ] &&
     grep -qE "writing checkpoint .*checkpoint.bin failed: No space left on device \([0-9]+ kB left\); free disk space" "$tmp/err"
  then echo "ok: a full file system -> $(cat "$tmp/err")"; else echo "FAIL: a full file system -> rc=$rc:"; cat "$tmp/err"; fail=1; fi
else
  echo "skipped: this system lets no test mount a file system (unshare -rm, mount -t tmpfs), so a real full disk is not tried"
fi
# A scene far beyond the machine's memory is refused before its particles are created, naming the
# figures, instead of filling the memory until the kernel kills the run: every built-in lattice case
# counts its particles first, so the refusal fits in 400 MB of address space.
huge() {  # <label> <options...>: refused in one line, before allocating
  (ulimit -v 400000; timeout 120 "$sph" "${@:2}" -nx 100000 -progress 0 -output_dir "$tmp/huge" >"$tmp/out" 2>"$tmp/err"); rc=$?
  if [ $rc -eq 1 ] && [ "$(grep -c . "$tmp/err")" -eq 1 ] &&
     grep -qE "the scene has at least [0-9.e+]+ particles on a node; at about [0-9.]+ kB a particle \(-solver [a-z]+, measured\) they need .* GB, more than its .* GB; lower -nx" "$tmp/err"
  then echo "ok: $1 -nx 100000 -> $(cat "$tmp/err")"; else echo "FAIL: $1 -nx 100000 -> rc=$rc:"; cat "$tmp/err"; fail=1; fi
}
huge taylor_green -case taylor_green
huge "dam_break 3D" -case dam_break -dim 3
huge lid_driven_cavity -case lid_driven_cavity -solver wcsph
huge still_water -case still_water
huge elliptical_drop -case elliptical_drop
huge square_patch -case square_patch
huge standing_wave -case standing_wave
huge sedov -case sedov -solver compressible
huge beltrami -case beltrami
[ ! -e "$tmp/huge" ] || { echo "FAIL: the refused scene created its output folder"; fail=1; }
exit $fail
