#!/usr/bin/env bash
# Checkpoints cannot lie: a restart with other options is refused naming the option, a changed byte
# (data or header) is refused, and a restart with the same options (a default spelled out included)
# or other numerics of the steps to come (-cfl, -dt, -ppe_ksp_*) is accepted; older checkpoints are kept.   usage: checkpoint.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
run="-case taylor_green -solver isph -nx 8 -t_end 0.04 -checkpoint_interval 0.02 -progress 0"
expect_ok $run -max_steps 4 -output_dir "$tmp/a"
ck="$tmp/a/checkpoint.bin"
[ -f "$ck" ] && [ ! -e "$ck.tmp" ] || { echo "FAIL: no checkpoint (or a leftover .tmp)"; fail=1; }

expect_error "written with -re unset.*this run has -re 400.*same -re" $run -re 400 -restart "$ck" -output_dir "$tmp/b"
expect_error "written with -kernel unset.*-kernel cubic_spline" $run -kernel cubic_spline -restart "$ck" -output_dir "$tmp/b"
expect_error "written with -case taylor_green.*-case square_patch" ${run/taylor_green/square_patch} -restart "$ck" -output_dir "$tmp/b"
expect_error "written with -solver isph.*-solver wcsph" ${run/isph/wcsph} -restart "$ck" -output_dir "$tmp/b"
expect_error "-nx 8.*-nx 16" $run -nx 16 -restart "$ck" -output_dir "$tmp/b"
expect_ok $run -re 100 -restart "$ck" -output_dir "$tmp/c"  # 100 is the default
expect_ok $run -t_end 0.06 -restart "$ck" -output_dir "$tmp/d"  # continuing further is allowed
# Without -output_dir a restart continues in the checkpoint's folder, not in the default one.
cp -r "$(dirname "$ck")" "$tmp/own"
expect_ok $run -t_end 0.06 -restart "$tmp/own/checkpoint.bin"
expect_json "$tmp/own/summary.json" 's["status"] == "completed" and len(s["history"]) == 2 and abs(s["history"][-1]["t"][1] - 0.06) < 1e-9' "a restart without -output_dir continues in the checkpoint's folder"
# A failing run is rescued with a smaller step or another linear solver: the numerics of the steps to
# come may change on restart, and the change is recorded in the history.
expect_ok $run -t_end 0.06 -cfl 0.1 -dt 0.004 -ppe_ksp_type bcgs -restart "$ck" -output_dir "$tmp/e"
expect_json "$tmp/e/summary.json" 's["status"] == "completed" and s["history"][-1]["numerics_changed"] == {"cfl": {"was": "default", "now": "0.1"}, "dt": {"was": "default", "now": "0.004"}, "ppe_ksp_type": {"was": "default", "now": "bcgs"}} and "numerics_changed" not in s["history"][0]' "a restart with other numerics records them"
expect_error "same -shift_coefficient" $run -shift_coefficient 1.5 -restart "$ck" -output_dir "$tmp/b"  # the scheme, not its numerics

# -checkpoints_kept K keeps the K newest, newest first; a run restarted from an older one (to go back
# to before a blow-up) continues in place.
k="$tmp/kept"
expect_ok $run -t_end 0.1 -checkpoints_kept 3 -output_dir "$k"
times() { for f in "$@"; do python3 -c 'import json,struct,sys; b=open(sys.argv[1],"rb").read(); n=struct.unpack("<Q",b[-24:-16])[0]; print(round(json.loads(b[-24-n:-24])["t"], 6))' "$f"; done | tr '\n' ' '; }
kept_t=$(times "$k/checkpoint.bin" "$k/checkpoint.bin.1" "$k/checkpoint.bin.2")
python3 -c 'import sys; t = [float(x) for x in sys.argv[1:]]; sys.exit(not (len(t) == 3 and t[0] == 0.1 and t[0] > t[1] > t[2] > 0))' $kept_t \
  && [ ! -e "$k/checkpoint.bin.3" ] && echo "ok: -checkpoints_kept 3 kept t = $kept_t" \
  || { echo "FAIL: -checkpoints_kept 3 kept $(ls "$k" | grep checkpoint | tr '\n' ' ') at t = $kept_t"; fail=1; }
oldest=$(times "$k/checkpoint.bin.2")
expect_ok $run -t_end 0.1 -checkpoints_kept 3 -cfl 0.1 -restart "$k/checkpoint.bin.2" -output_dir "$k"
expect_json "$k/summary.json" "s['status'] == 'completed' and abs(s['history'][-1]['t'][0] - $oldest) < 1e-6 and 'cfl' in s['history'][-1]['numerics_changed']" "restarted from the oldest kept checkpoint, with a smaller step"
expect_error "-checkpoints_kept must be between 1 and 1000" $run -checkpoints_kept 0 -output_dir "$tmp/b"

# Two bytes changed in the data, then a time edited in the header.
cp "$ck" "$tmp/data.bin"
python3 - "$tmp/data.bin" <<'PY'
import sys
b = bytearray(open(sys.argv[1], "rb").read()); b[200] ^= 1; b[201] ^= 4
open(sys.argv[1], "wb").write(b)
PY
expect_error "fails its checksum" $run -restart "$tmp/data.bin" -output_dir "$tmp/b"
cp "$ck" "$tmp/header.bin"
python3 - "$tmp/header.bin" <<'PY'
import re, sys
b = open(sys.argv[1], "rb").read()
open(sys.argv[1], "wb").write(re.sub(rb'"t":[0-9][0-9.e+-]*', b'"t":0.5', b, count=1))
PY
expect_error "fails its header checksum" $run -restart "$tmp/header.bin" -output_dir "$tmp/b"
head -c 3000 "$ck" >"$tmp/short.bin"
expect_error "damaged or incomplete" $run -restart "$tmp/short.bin" -output_dir "$tmp/b"
expect_error "cannot read checkpoint" $run -restart "$tmp/none.bin" -output_dir "$tmp/b"
expect_error "-restart .*/a is a folder; give its checkpoint file \(.*/a/checkpoint.bin\)" $run -restart "$tmp/a" -output_dir "$tmp/b"
exit $fail
