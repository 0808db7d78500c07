#!/usr/bin/env bash
# Crashes around checkpoint writes lose nothing: a run killed (SIGKILL, as a power cut) at random
# points of its checkpoint writes (data written, trailer written, renamed; SPH_FAULT_CHECKPOINT) or
# at a random time is resumed from whatever checkpoint.bin it left (from scratch if none), and ends
# with the uninterrupted run's final state, bit for bit, and its time series.
#   usage: fault_injection.sh <sph executable> <source dir>; SEED=n repeats a sequence.
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
seed=${SEED:-$$}; RANDOM=$seed; echo "seed $seed"
run="-case taylor_green -solver isph -nx 16 -t_end 0.3 -checkpoint_interval 0.02 -output_interval 0.04 -progress 0"
"$sph" $run -output_dir "$tmp/whole" >/dev/null 2>&1 || { echo "FAIL: uninterrupted run"; exit 1; }
# state <checkpoint>: field data and the header's t, step and scalars (not the record of the runs).
state() {
  python3 - "$1" <<'PY'
import hashlib, json, struct, sys
b = open(sys.argv[1], "rb").read()
n = struct.unpack("<Q", b[-24:-16])[0]
h = json.loads(b[-24 - n:-24])
print(hashlib.sha256(b[:h["data_bytes"]]).hexdigest(), json.dumps([h["t"], h["step"], h["scalars"]], sort_keys=True))
PY
}
want=$(state "$tmp/whole/checkpoint.bin")
crash_and_resume() {  # <label> <env assignment or ""> <seconds before SIGKILL or "">
  local d="$tmp/$1"
  env $2 "$sph" $run -output_dir "$d" >/dev/null 2>&1 &
  local pid=$!
  [ -n "$3" ] && { sleep "$3"; kill -KILL $pid 2>/dev/null; }
  wait $pid 2>/dev/null
  local from="from scratch"
  if [ -f "$d/checkpoint.bin" ]; then
    from="from step $(python3 -c 'import json,struct,sys; b=open(sys.argv[1],"rb").read(); n=struct.unpack("<Q",b[-24:-16])[0]; print(json.loads(b[-24-n:-24])["step"])' "$d/checkpoint.bin")"
    "$sph" $run -output_dir "$d" -restart "$d/checkpoint.bin" >"$tmp/log" 2>&1
  else
    "$sph" $run -output_dir "$d" -overwrite >"$tmp/log" 2>&1
  fi || { echo "FAIL: $1: resuming failed:"; cat "$tmp/log"; fail=1; return; }
  if [ "$(state "$d/checkpoint.bin")" = "$want" ] && cmp -s "$d/timeseries.csv" "$tmp/whole/timeseries.csv" &&
     [ ! -e "$d/checkpoint.bin.tmp" ]; then
    echo "ok: $1 ($2 ${3:+killed after $3 s}), resumed $from: final state and time series as uninterrupted"
  else
    echo "FAIL: $1 ($2 $3), resumed $from: final state or time series differ"; fail=1
  fi
}
for stage in data trailer renamed; do
  for k in 1 2; do
    n=$((RANDOM % 12 + 1))
    crash_and_resume "$stage$k" "SPH_FAULT_CHECKPOINT=$stage:$n" ""
  done
done
for k in 1 2 3; do
  crash_and_resume "timed$k" "" "$(python3 -c "import random; random.seed($seed + $k); print(round(random.uniform(0.3, 1.5), 2))")"
done
exit $fail
