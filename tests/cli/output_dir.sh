#!/usr/bin/env bash
# One output directory holds one run: a directory holding a run is refused (nothing in it touched)
# unless -overwrite, which leaves no stale frame or MPI piece behind; a restart in place drops the
# frames of the abandoned future.   usage: output_dir.sh <sph executable> <source dir>; $MPIEXEC names mpiexec.
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mpiexec="${MPIEXEC:-mpiexec}"
fail=0
source "$(dirname "$0")/lib/expect.sh"
d="$tmp/run"
run="-case taylor_green -solver isph -nx 8 -t_end 0.1 -progress 0 -output_dir $d"
expect_ok $run -output_interval 0.01
frames() { ls "$d" | grep -cE '^particles_[0-9]+(_r[0-9]+)?\.(vtp|pvtp)$'; }
listed() { grep -c '<DataSet' "$d/particles.pvd"; }
before=$(md5sum "$d/summary.json")
expect_error "already holds a run.*-overwrite" $run -output_interval 0
[ "$(md5sum "$d/summary.json")" = "$before" ] || { echo "FAIL: a refused run changed the old summary"; fail=1; }

expect_ok $run -output_interval 0 -overwrite
[ "$(frames)" -eq 2 ] && [ "$(listed)" -eq 2 ] || { echo "FAIL: -overwrite left $(frames) frames (want 2)"; ls "$d"; fail=1; }
"$mpiexec" -n 2 "$sph" $run -output_interval 0 -overwrite >/dev/null 2>&1 || { echo "FAIL: 2-rank -overwrite run"; fail=1; }
expect_ok $run -output_interval 0 -overwrite
if ls "$d" | grep -qE '_r[0-9]+\.vtp|\.pvtp'; then echo "FAIL: MPI pieces left after a serial -overwrite"; fail=1
else echo "ok: no MPI pieces left after a serial -overwrite"; fi

# Restart in place from t = 0.05: the later frames of the first run go, the series is rewritten.
expect_ok $run -output_interval 0.01 -checkpoint_interval 0.05 -overwrite -max_steps 1000
cp "$d/checkpoint.bin" "$tmp/mid.bin" 2>/dev/null
expect_ok $run -output_interval 0.01 -checkpoint_interval 0.05 -overwrite -t_end 0.05
expect_ok $run -output_interval 0.01 -checkpoint_interval 0.05 -restart "$d/checkpoint.bin"
[ "$(frames)" -eq "$(listed)" ] || { echo "FAIL: $(frames) frames on disk, $(listed) in particles.pvd"; fail=1; }
exit $fail
