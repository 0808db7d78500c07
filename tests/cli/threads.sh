#!/usr/bin/env bash
# OpenMP threads change no result: the same runs with -threads 1 and -threads 2 give bitwise the same
# error norms (tolerance 0) and the same KSP iterations, for ISPH (periodic, walls, free surface),
# WCSPH and the compressible solver. The pair loops sum each particle's pairs in list order on one
# thread; the threaded neighbour search joins its blocks in order; hypre gave identical iterates here
# too.   usage: threads.sh <sph executable> <source dir>; $MPIEXEC names mpiexec.
set -u
sph="$1"; src="$2"; tmp=${KEEP_TMP:-$(mktemp -d)}; [ -n "${KEEP_TMP:-}" ] || trap 'rm -rf "$tmp"' EXIT
mpiexec="${MPIEXEC:-mpiexec}"
fail=0
source "$(dirname "$0")/lib/compare_runs.sh"

# same_on_1_and_2_threads <label> <args...>
same_on_1_and_2_threads() {
  local label="$1"; shift
  run "$label-t1" 1 "$@" -threads 1
  run "$label-t2" 1 "$@" -threads 2
  compare "$label-t1" "$label-t2" 0
}
same_on_1_and_2_threads isph -case taylor_green -solver isph -nx 32 -t_end 0.3
same_on_1_and_2_threads wcsph -case taylor_green -solver wcsph -nx 32 -t_end 0.1
same_on_1_and_2_threads cavity -case lid_driven_cavity -solver isph -nx 16 -t_end 0.3
same_on_1_and_2_threads dam -case dam_break -solver isph -nx 12 -t_end 0.3
same_on_1_and_2_threads sod -options_file "$src/cases/sod.opts" -nx 200 -t_end 0.1
same_on_1_and_2_threads sedov -options_file "$src/cases/sedov.opts" -nx 32
exit $fail
