#!/usr/bin/env bash
# Every KSP x PC choice runs the ISPH pressure solve on every step (the KSP is made anew per step from
# the options database), on 1 and 2 MPI ranks, on Taylor-Green (periodic) and the cavity (walls, a
# closed domain). Each run must complete; its viewers (-ppe_ksp_view, -ppe_ksp_converged_reason,
# -ppe_ksp_view_final_residual, -ppe_ksp_monitor_true_residual, -ppe_pc_view, -mat_view) must print
# once per solve; and its error norms must equal the default solver's to the solver tolerance.
#   usage: solver_matrix.sh <sph executable> <source dir>; $MPIEXEC names mpiexec.
set -u
sph="$1"; src="$2"; tmp=${KEEP_TMP:-$(mktemp -d)}; [ -n "${KEEP_TMP:-}" ] || trap 'rm -rf "$tmp"' EXIT
mpiexec="${MPIEXEC:-mpiexec}"
fail=0
source "$(dirname "$0")/lib/compare_runs.sh"
steps=2
views="-ppe_ksp_view -ppe_ksp_converged_reason -ppe_ksp_view_final_residual -ppe_ksp_monitor_true_residual -ppe_pc_view -mat_view ::ascii_info"

# viewed <label> <solves per step>: each viewer printed once per solve (top-level objects start a line;
# sub-solvers' are indented). Two solves a step: the projection and its correction pass
# (-projection_corrections 1, the default), on the cavity as on Taylor-Green.
viewed() {
  local log="$tmp/$1.log" n k
  n=$(python3 -c "import csv,sys; print($2 * sum(1 for _ in csv.DictReader(open(sys.argv[1]))))" "$tmp/$1/timeseries.csv" 2>/dev/null || echo 0)
  local -a want=("^KSP Object:" "$n" "^PC Object:" $((2 * n)) "^Mat Object:" "$n" "^Linear ppe_ solve converged" "$n"
                 "^KSP final norm of residual" "$n" "^ *0 KSP .*true resid norm" "$n")
  for ((k = 0; k < ${#want[@]}; k += 2)); do
    local got; got=$(grep -cE -- "${want[k]}" "$log")
    if [ "$n" -ne $(($2 * steps)) ] || [ "$got" -ne "${want[k + 1]}" ]; then
      echo "FAIL: $1: '${want[k]}' printed $got times in $n solves (want ${want[k + 1]})"; fail=1
    fi
  done
}

# matrix <name> <ranks> <case options> -- <solver choice>...: each choice (a quoted option list) against the default.
matrix() {
  local name="$1" n="$2" opts="$3"; shift 4
  local per_step=2
  run "$name-default-$n" "$n" $opts
  local k=0
  for choice in "$@"; do
    k=$((k + 1))
    run "$name-$k-$n" "$n" $opts $choice $views
    viewed "$name-$k-$n" "$per_step"
    echo "  ($name-$k-$n: $choice)"
    compare "$name-default-$n" "$name-$k-$n" 1e-7 any
  done
}

tgv="-case taylor_green -nx 12 -max_steps $steps -ppe_ksp_rtol 1e-10"
classic="$tgv -isph_operators classic"  # symmetric matrix: CG, ICC
cavity="-case lid_driven_cavity -nx 10 -max_steps $steps -ppe_ksp_rtol 1e-10"
parallel=("" "-ppe_pc_type gamg" "-ppe_pc_type bjacobi -ppe_sub_pc_type ilu" "-ppe_pc_type asm -ppe_sub_pc_type ilu"
          "-ppe_pc_type jacobi" "-ppe_pc_type sor" "-ppe_pc_type none" "-ppe_pc_hypre_type euclid"
          "-ppe_pc_hypre_type pilut -ppe_pc_hypre_pilut_factorrowsize 40" "-ppe_ksp_type bcgs"
          "-ppe_ksp_type fgmres -ppe_pc_type gamg" "-mat_type baij")
# On 2 ranks: the preconditioners that run in parallel (not the sequential factorisations).
parallel2=("" "-ppe_pc_type gamg" "-ppe_pc_type bjacobi -ppe_sub_pc_type ilu" "-ppe_pc_type asm -ppe_sub_pc_type ilu"
           "-ppe_pc_type jacobi" "-ppe_pc_type sor" "-ppe_pc_type none" "-ppe_pc_hypre_type euclid"
           "-ppe_pc_hypre_type pilut -ppe_pc_hypre_pilut_factorrowsize 40")
serial=("-ppe_pc_type ilu" "-ppe_pc_type lu" "-ppe_ksp_type bcgs -ppe_pc_type ilu")
symmetric=("" "-ppe_pc_type icc" "-ppe_pc_type gamg" "-ppe_pc_type jacobi" "-ppe_ksp_type minres"
           "-ppe_pc_type bjacobi -ppe_sub_pc_type icc")
# A closed domain's singular system is regularised (solvers/isph/pressure_poisson.cpp, assemble): its
# near-null mode needs more than a one-level preconditioner, and without one the run stops saying so.
one_level=("-ppe_pc_type jacobi" "-ppe_pc_type none")
without_one_level() { local c; for c in "$@"; do [[ " ${one_level[*]} " == *" $c "* ]] || printf '%s\n' "$c"; done; }
mapfile -t closed < <(without_one_level "${parallel[@]}")
mapfile -t closed2 < <(without_one_level "${parallel2[@]}")
matrix tgv 1 "$tgv" -- "${parallel[@]}" "${serial[@]}"
matrix cavity 1 "$cavity" -- "${closed[@]}" "${serial[@]}"
matrix classic 1 "$classic -ppe_ksp_type cg" -- "${symmetric[@]}"
# Re-partitioning every step changes each rank's rows between solves.
matrix tgv 2 "$tgv -partition_interval 1" -- "${parallel2[@]}"
matrix cavity 2 "$cavity -partition_interval 1" -- "${closed2[@]}"
source "$(dirname "$0")/lib/expect.sh"
for c in "${one_level[@]}"; do
  expect_error "did not converge .*: with no free surface the pressure system is singular.*use a multigrid one" \
    $cavity $c -ppe_ksp_max_it 200 -output_dir "$tmp/one-level" -overwrite -progress 0
done
# Out of iterations: the advice is more iterations or a stronger preconditioner, not a smaller step
# (the Laplacian does not depend on dt).
expect_error "DIVERGED_ITS after 1 iterations.*; raise -ppe_ksp_max_it \(now 1\) or choose a stronger -ppe_pc_type" \
  -case dam_break -nx 10 -ppe_ksp_max_it 1 -max_steps 3 -output_dir "$tmp/max-it" -progress 0
exit $fail
