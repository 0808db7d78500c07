#!/usr/bin/env bash
# A checkpoint is an output: a run that writes frames and checkpoints often has the time series of
# one that writes none, byte for byte, and a restart from one written mid-run, on as many ranks,
# continues it byte for byte (ISPH and WCSPH, a free surface between walls, a periodic box, a thin
# plate; 1 and 2 ranks). On another rank count, or from a checkpoint without the record of the particles' order (an
# older one), the restart says that it continues in the curve's order.
#   usage: neutral_checkpoints.sh <sph executable> <source dir>; $MPIEXEC names mpiexec.
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
mpiexec="${MPIEXEC:-mpiexec}"
fail=0
# go <ranks> <args...>: a run that must complete.
go() {
  local n="$1"; shift
  "$mpiexec" -n "$n" "$sph" "$@" >"$tmp/log" 2>&1 || { echo "FAIL: sph $* on $n ranks exited non-zero:"; tail -5 "$tmp/log"; fail=1; }
}
same() {  # <what> <file> <file>
  if cmp -s "$2" "$3"; then echo "ok: $1"; else echo "FAIL: $1: $(diff "$2" "$3" | head -3 | tr '\n' ' ')"; fail=1; fi
}
# The dam break's walls and free surface (long enough for a checkpoint's re-ordering, as it was, to
# show in the rows), and a periodic box at a fixed step, whose rebuilds wrap the positions: a restart
# that built the lists at the current positions, not the recorded ones, wraps them at another step
# (measured: rows differ from step 23 on).
# The baffle's thin plate: its screens at the particles' places at the checkpoint, not where the lists
# were built.
for s in isph wcsph taylor_green baffle; do
  case $s in
    baffle) run="-case scene -scene_file $src/cases/scenes/baffle_sloshing.yaml -nx 10 -solver isph -t_end 0.5" every=0.05 ;;
    isph) run="-case dam_break -nx 10 -solver isph -t_end 0.3" every=0.03 ;;
    wcsph) run="-case dam_break -nx 10 -solver wcsph -t_end 0.2" every=0.02 ;;
    taylor_green) run="-case taylor_green -nx 16 -solver isph -t_end 0.2 -dt 0.005" every=0.02 ;;
  esac
  run="$run -threads 1 -progress 0"
  for n in 1 2; do
    d="$tmp/$s-$n"
    go $n $run -output_interval 0 -output_dir "$d-quiet"
    go $n $run -output_interval $every -checkpoints_kept 6 -output_dir "$d-often"
    same "$s, $n rank(s): a frame and a checkpoint every $every change no row of timeseries.csv" \
      "$d-quiet/timeseries.csv" "$d-often/timeseries.csv"
    # In place from the checkpoint written halfway (checkpoint.bin.5 of ten): the rows after it again.
    cp -r "$d-often" "$d-resumed"
    go $n $run -output_interval $every -checkpoints_kept 6 -restart "$d-resumed/checkpoint.bin.5"
    grep -q "curve's order" "$tmp/log" && { echo "FAIL: $s, $n rank(s): the restart fell back to the curve"; fail=1; }
    same "$s, $n rank(s): resumed halfway, the time series of the uninterrupted run" \
      "$d-quiet/timeseries.csv" "$d-resumed/timeseries.csv"
  done
done

# Another rank count: the particles in the curve's order, said in one line.
cp -r "$tmp/isph-2-often" "$tmp/moved"
go 1 -case dam_break -nx 10 -solver isph -t_end 0.3 -threads 1 -progress 0 -output_interval 0.03 -restart "$tmp/moved/checkpoint.bin.5"
grep -q "^restart: 1 rank, the checkpoint was written on 2: continuing from the curve's order; results match the uninterrupted run to round-off, not bitwise$" "$tmp/log" &&
  echo "ok: a 2-rank checkpoint resumed on 1 rank says so" || { echo "FAIL: no line on the rank count:"; cat "$tmp/log"; fail=1; }
# An older checkpoint, without the record (taken out here, checksums made again), resumes the same way.
cp -r "$tmp/isph-1-often" "$tmp/older"
python3 - "$tmp/older/checkpoint.bin.5" <<'PY' || fail=1
import json, struct, sys
path = sys.argv[1]
b = open(path, "rb").read()
n = struct.unpack("<Q", b[-24:-16])[0]
h = json.loads(b[-24 - n:-24])
fields, ids = h["fields"], h["n_ids"]
record = [f for f in fields if f["name"] in ("storage_index", "x_at_build")]
assert len(record) == 2 and fields[-2:] == record and "order" in h["run"], "no record of the order in the checkpoint"
head = (h["data_bytes"] - 8 * ids * sum(f["components"] for f in fields)) // len(fields)  # each vector's
cut = h["data_bytes"] - sum(head + 8 * ids * f["components"] for f in record)
def fnv1a(data):
    x = 1469598103934665603
    for c in data: x = ((x ^ c) * 1099511628211) % 2**64
    return x
h["fields"] = fields[:-2]
del h["run"]["order"]
h["data_bytes"], h["data_checksum"] = cut, fnv1a(b[:cut])
text = json.dumps(h).encode()
open(path, "wb").write(b[:cut] + text + struct.pack("<QQ", len(text), fnv1a(text)) + b"SPHCKPT1")
PY
go 1 -case dam_break -nx 10 -solver isph -t_end 0.3 -threads 1 -progress 0 -output_interval 0.03 -restart "$tmp/older/checkpoint.bin.5"
grep -q "^restart: the checkpoint has no record of its particles' order: continuing from the curve's order" "$tmp/log" &&
  echo "ok: a checkpoint without the record resumes in the curve's order and says so" || { echo "FAIL: no line on the older checkpoint:"; cat "$tmp/log"; fail=1; }
exit $fail
