#!/usr/bin/env bash
# A tank swaying sideways (cases/scenes/moving_tank.yaml): the water's horizontal force on it against
# linear potential theory (scripts/forced-sloshing-check), over the first two seconds. ISPH converges
# towards the theory with the spacing (RMS error 8.8 % of the largest force at nx 20, 4.1 % at nx 40
# when this was written: the test asks for a fall by 1.5 times and 6 %); WCSPH at nx 20 reads 9.1 %
# (bound 12 %). docs/verification/moving_tank.md.
#   usage: moving_tank.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
run="-case scene -scene_file $src/cases/scenes/moving_tank.yaml -t_end 2 -progress 0 -threads 1 -output_interval 0 -checkpoint_interval 0"
expect_ok $run -nx 20 -solver isph -output_dir "$tmp/isph-20"
expect_ok $run -nx 40 -solver isph -output_dir "$tmp/isph-40"
expect_ok $run -nx 20 -solver wcsph -output_dir "$tmp/wcsph-20"
"$src/scripts/forced-sloshing-check" "$tmp/isph-20" "$tmp/isph-40" "$tmp/wcsph-20" --until 2 >"$tmp/check" || fail=1
cat "$tmp/check"
PYTHONPATH="$(dirname "$0")/lib" /usr/bin/python3 -B - "$tmp/check" <<'PY' || fail=1
import sys
from checks import check, finish
err = {line.split()[0].rstrip("/").split("/")[-1]: float(line.split()[2])
       for line in open(sys.argv[1]) if not line.startswith("run")}
check(err["isph-40"] < err["isph-20"] / 1.5, f"ISPH converges to linear theory: {err['isph-20']:.4f} at nx 20, "
      f"{err['isph-40']:.4f} at nx 40")
check(err["isph-40"] < 0.06, f"ISPH at nx 40 within 6 % of the largest force ({err['isph-40']:.4f})")
check(err["wcsph-20"] < 0.12, f"WCSPH at nx 20 within 12 % ({err['wcsph-20']:.4f})")
finish()
PY
exit $fail
