#!/usr/bin/env bash
# Checkpoints cannot lie: a restart with other options is refused naming the option, a changed byte
# (data or header) is refused, and a restart with the same options (a default spelled out included)
# is accepted.   usage: checkpoint.sh <sph executable> <source dir>
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
exit $fail
