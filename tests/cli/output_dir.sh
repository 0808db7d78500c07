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

# One run per directory: its lock is held for the whole run, so a second run started into it is
# refused, naming the holder, even before the first has written anything.
l="$tmp/locked"; mkdir -p "$l"
exec 9>"$l/.sph.lock"; flock 9  # this shell holds the lock
expect_error "output directory .*locked is in use by another run" $run -output_dir "$l"
exec 9>&-
rm "$l/.sph.lock"
[ -z "$(ls "$l")" ] || { echo "FAIL: a refused run wrote into a locked directory: $(ls "$l")"; fail=1; }
"$sph" -case taylor_green -nx 32 -t_end 1 -progress 0 -output_dir "$tmp/busy" >/dev/null 2>&1 & first=$!
for k in $(seq 50); do grep -q "pid $first" "$tmp/busy/.sph.lock" 2>/dev/null && break; sleep 0.1; done
expect_error "output directory .*busy is in use by another run \(pid $first" $run -output_dir "$tmp/busy"
wait $first || { echo "FAIL: the first run did not complete beside the refused one"; fail=1; }
expect_json "$tmp/busy/summary.json" 's["status"] == "completed" and s["parameters"]["nx"] == 32' "the first run's summary is its own"
expect_error "already holds a run" $run -output_dir "$tmp/busy"

# A frame write that fails (here into /dev/full, as on a full disk) is named in one line and leaves
# no partial frame: earlier frames stay, the failed state is written where room remains.
f="$tmp/full"; mkdir -p "$f"; ln -s /dev/full "$f/particles_00002.vtp.tmp"
expect_error "cannot write .*particles_00002.vtp \(No space left on device\); free space" $run -output_dir "$f" -output_interval 0.02 -checkpoint_interval 0
[ ! -e "$f/particles_00002.vtp.tmp" ] || { echo "FAIL: the failed frame's temporary file was left"; fail=1; }
expect_json "$f/summary.json" 's["status"] == "failed" and "particles_00002.vtp" in s["failure"]' "the failed frame write is the run's recorded failure"
exit $fail
