#!/usr/bin/env bash
# Command-line behaviour: bad input gives one line naming the cause and a non-zero exit; -help lists
# the options with their defaults.   usage: options.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
# Runs refused only after their first step have written a frame: each replaces the last one.
small="-case taylor_green -nx 8 -t_end 0.01 -progress 0 -output_dir $tmp/out -overwrite"
expect_error "unknown option -foo" $small -foo 1
expect_error "did you mean -shifting" $small -shiftng 0
expect_error "unknown option -ppe_ksp_typo" $small -ppe_ksp_typo cg
expect_error "did you mean -ppe_ksp_type" $small -ppe_ksp_tpye cg
expect_error "did you mean -c0" -case taylor_green -solver wcsph -nx 8 -c00 3
# The two choices every run makes are suggested too (-cas once suggested -a0).
expect_error "unknown option -cas .*did you mean -case\?" -cas taylor_green -nx 8 -t_end 0.01 -progress 0 -output_dir "$tmp/out" -overwrite
expect_error "unknown option -solvr .*did you mean -solver\?" $small -solvr isph
# Every option is checked, PETSc's own included (those read at start-up, during a solve, at the end).
expect_error "unknown option -options_fiel .*did you mean -options_file\?" $small -options_fiel x.opts
expect_error "unknown option -log_veiw .*did you mean -log_view\?" $small -log_veiw
expect_error "unknown option -ppe_ksp_converged_reson .*did you mean -ppe_ksp_converged_reason\?" $small -ppe_ksp_converged_reson
# Options read only by the first solve are checked after it.
expect_error "option -ppe_sub_pc_typ was not used by the first step.*did you mean -ppe_sub_pc_type\?" $small -ppe_pc_type bjacobi -ppe_sub_pc_typ ilu
expect_error "option -mat_tpye was not used by the first step.*did you mean -mat_type\?" $small -mat_tpye aij
expect_error "option -ppe_sub_pc_type was not used by the first step" $small -ppe_sub_pc_type ilu
# A valid option given to the wrong solver or case names the one that reads it.
expect_error "option -ppe_ksp_type is read by -solver isph, not by this run's -case taylor_green and -solver wcsph" $small -solver wcsph -ppe_ksp_type gmres
expect_error "option -ppe_ksp_converged_reason is read by -solver isph" $small -solver wcsph -ppe_ksp_converged_reason
# The pressure solve's PETSc options carry the prefix ppe_: the old spellings are refused naming the
# new one (with any solver, at start-up, those read only during a solve too), and a typo of an old
# one is suggested the new spelling.
expect_error "^sph: error: option -ksp_rtol is now -ppe_ksp_rtol: the pressure solve's options carry the prefix ppe_$" $small -ksp_rtol 1e-6 -output_dir "$tmp/old"
[ -e "$tmp/old" ] && { echo "FAIL: a run given an old spelling started"; fail=1; }
# Given both ways, the old name is still refused, and the new one's value is kept for the check.
expect_error "option -ksp_rtol is now -ppe_ksp_rtol" $small -ksp_rtol 1e-6 -ppe_ksp_rtol 1e-7
expect_error "option -pc_type is now -ppe_pc_type: the pressure solve's options carry the prefix ppe_" $small -pc_type gamg
expect_error "option -pc_hypre_boomeramg_strong_threshold is now -ppe_pc_hypre_boomeramg_strong_threshold" $small -pc_hypre_boomeramg_strong_threshold 0.5
expect_error "option -ksp_converged_reason is now -ppe_ksp_converged_reason" $small -ksp_converged_reason
expect_error "option -pc_view is now -ppe_pc_view" $small -pc_view
expect_error "option -ksp_monitor is now -ppe_ksp_monitor" $small -solver wcsph -ksp_monitor
expect_error "option -sub_pc_type is now -ppe_sub_pc_type" $small -ppe_pc_type bjacobi -sub_pc_type ilu
expect_error "option -mat_mumps_icntl_4 is now -ppe_mat_mumps_icntl_4" $small -ppe_pc_type lu -mat_mumps_icntl_4 2
expect_error "unknown option -ksp_tpye .*did you mean -ppe_ksp_type\?" $small -ksp_tpye cg
expect_error "option -c0 is read by -solver wcsph, not by this run's -case taylor_green and -solver isph" $small -c0 10
# One name per Courant number: -cfl is ISPH's advective one, -acoustic_cfl the explicit schemes'.
expect_error "^sph: error: option -cfl is now -acoustic_cfl: the explicit schemes' step is set by the acoustic Courant number; -cfl is ISPH's advective one$" $small -solver wcsph -cfl 0.2
expect_error "option -cfl is now -acoustic_cfl" -case sod -solver compressible -nx 48 -cfl 0.2 -progress 0 -output_dir $tmp/out -overwrite
expect_error "option -acoustic_cfl is read by -solver wcsph, -solver compressible, not by this run's -case taylor_green and -solver isph" $small -acoustic_cfl 0.2
expect_error "-acoustic_cfl must be in \(0, 1\]" $small -solver wcsph -acoustic_cfl 2
expect_error "option -wall_layers is read by -case lid_driven_cavity.*-case poiseuille" $small -wall_layers 4
# A scheme's own operator choices carry its prefix: the old shared name is told the chosen scheme's
# new one, and one scheme's option given to the other names its owner.
expect_error "^sph: error: option -operators is now -wcsph_operators: the schemes' own operator choices carry their prefix" $small -solver wcsph -operators classic
expect_error "option -operators is now -isph_operators" $small -operators classic
expect_error "option -pressure_gradient is now -isph_pressure_gradient" $small -pressure_gradient symmetric
expect_error "option -pressure_gradient is now -wcsph_pressure_gradient" $small -solver wcsph -pressure_gradient symmetric
expect_error "option -wcsph_operators is read by -solver wcsph, not by this run's -case taylor_green and -solver isph" $small -wcsph_operators classic
expect_error "option -isph_pressure_gradient is read by -solver isph, not by this run's" $small -solver wcsph -isph_pressure_gradient symmetric
expect_error "unknown option -isph_operatrs .*did you mean -isph_operators\?" $small -isph_operatrs classic
for name in -isph_operators -isph_pressure_gradient -wcsph_operators -wcsph_pressure_gradient -viscous_laplacian; do
  "$sph" -help 2>&1 | grep -q -- "^  $name <" || { echo "FAIL: -help does not list $name"; fail=1; }
done
expect_error "-lid_corners symmetric is 2D only" -case lid_driven_cavity -dim 3 -nx 8 -lid_corners symmetric -progress 0 -output_dir $tmp/out -overwrite
expect_error "option -profile_interpolation has the value 'foo', which is none of its choices \\(shepard, linear\\)$" -case lid_driven_cavity -nx 8 -profile_interpolation foo -progress 0 -output_dir $tmp/out -overwrite
# A mistyped choice is named with the choices and the nearest of them.
expect_error "option -case has the value 'dam_brek', which is none of its choices \\(taylor_green, .*\\); did you mean dam_break\\?$" -case dam_brek -progress 0 -output_dir $tmp/out -overwrite
expect_error "option -solver has the value 'ispf', which is none of its choices \\(isph, wcsph, compressible\\); did you mean isph\\?$" $small -solver ispf
expect_error "-profile_average_from must be a time >= 0" -case lid_driven_cavity -nx 8 -profile_average_from -2 -progress 0 -output_dir $tmp/out -overwrite
expect_error "-profile_average_from needs a reference" -case lid_driven_cavity -nx 8 -re 200 -profile_average_from 1 -progress 0 -output_dir $tmp/out -overwrite
expect_error "-mat_type seqsbaij stores half of a symmetric matrix" $small -mat_type sbaij
expect_error "-nx must be" $small -nx -3
expect_error "-re must be positive" $small -re 0
expect_error "unknown case|Unknown|case" -case no_such_case
expect_error "-cfl must be" $small -cfl 5
expect_error "kernel" $small -kernel no_such_kernel
expect_error "options|file|PETSc" -options_file "$tmp/missing.opts"
# An option that needs a value and has none was dropped by PETSc (the default ran): refused, on the
# command line and in an options file alike. A flag may stand alone.
bare="-case taylor_green -t_end 0.01 -progress 0 -output_dir $tmp/out -overwrite"
expect_error "option -nx was given without a value \(its default is 64\)" $bare -nx -re 50
expect_error "option -re was given without a value" $bare -nx 8 -re
expect_error "option -restart was given without a value" $bare -nx 8 -restart
expect_error "option -output_dir was given without a value" -case taylor_green -nx 8 -t_end 0.01 -progress 0 -output_dir
expect_error "option -case was given without a value" -case -nx 8
expect_error "option -ppe_ksp_rtol was given without a value" $bare -nx 8 -ppe_ksp_rtol
printf -- '-nx\n-t_end 0.01\n' > "$tmp/bare.opts"
expect_error "option -nx was given without a value" -options_file "$tmp/bare.opts" -progress 0 -output_dir "$tmp/out" -overwrite
expect_ok $bare -nx 8 -shifting
# inf and nan parse as reals: refused before the run starts, which would fail at step 1 (or hang).
expect_error "option -t_end has the value 'inf', which is not a finite number" $bare -nx 8 -t_end inf
expect_error "option -cfl has the value 'nan', which is not a finite number" $bare -nx 8 -cfl nan
expect_error "option -dt has the value 'inf'" $bare -nx 8 -dt inf -dt_force 1
scene="-case scene -scene_file $src/cases/scenes/submerged_cylinder.yaml -nx 10 -t_end 0.01 -progress 0 -output_dir $tmp/out -overwrite"
expect_error "option -gravity has the value '0,inf', which is not a finite number" $scene -gravity 0,inf
expect_error "option -gravity was given without a value" $scene -gravity
# Options files PETSc would refuse with a traceback, or recurse into until it crashes.
printf -- '-nx 8\n-options_file %s\n' "$tmp/self.opts" > "$tmp/self.opts"
expect_error "options file '.*self.opts' includes itself" -options_file "$tmp/self.opts"
printf -- '-options_file %s\n' "$tmp/b.opts" > "$tmp/a.opts"; printf -- '-re 10\n-options_file %s\n' "$tmp/a.opts" > "$tmp/b.opts"
expect_error "options file '.*a.opts' includes itself" -options_file "$tmp/a.opts"
expect_error "options file '.*' \(-options_file\) is a folder" -options_file "$tmp"
printf -- '-nx 8 -re 10\n' > "$tmp/two.opts"
expect_error "two.opts' line 1: '-re' follows the value of -nx; put each option on a line of its own" -options_file "$tmp/two.opts"
printf -- '# a scene\n-nx 8  # particles per side\nnx 16\n' > "$tmp/garbage.opts"
expect_error "options file '.*garbage.opts' line 3: 'nx' is not an option" -options_file "$tmp/garbage.opts"
expect_error "option -nx has the value 'abc', which is not an integer" -case taylor_green -nx abc
expect_error "option -re has the value 'x1', which is not a number" -case taylor_green -re x1
expect_error "-ppe_ksp_rtol must be in \(0, 1\) \(got -1\)" $small -ppe_ksp_rtol -1
expect_error "-ppe_ksp_max_it must be at least 1" $small -ppe_ksp_max_it 0
expect_error "use -solver compressible" -case sod -solver wcsph -nx 48 -progress 0
expect_error "use -solver compressible" -case toy_star -solver isph -nx 50 -progress 0

# -help shows the pressure solve's defaults as a run gets them (GMRES, right preconditioning, with the
# consistent operators); a symmetric-only method on the non-symmetric matrix is warned against (with
# BoomerAMG it diverges at step 1), and a direct solve needs no first-guess option.
"$sph" -help 2>&1 | grep -q -- "-ppe_ksp_type <now gmres" && "$sph" -help 2>&1 | grep -q -- "-ppe_ksp_pc_side <now RIGHT" \
  && echo "ok: -help shows gmres and RIGHT" || { echo "FAIL: -help does not show the default KSP (gmres, RIGHT)"; fail=1; }
"$sph" -help -isph_operators classic 2>&1 | grep -q -- "-ppe_ksp_type <now cg" && echo "ok: -help -isph_operators classic shows cg" \
  || { echo "FAIL: -help -isph_operators classic does not show cg"; fail=1; }
"$sph" $small -ppe_ksp_type cg -max_steps 1 >/dev/null 2>"$tmp/stderr"
[ "$(grep -c "warning: -ppe_ksp_type cg assumes a symmetric matrix, and this run's pressure matrix is not" "$tmp/stderr")" -eq 1 ] \
  && echo "ok: -ppe_ksp_type cg on the non-symmetric matrix is warned against, once" || { echo "FAIL: no single cg warning:"; cat "$tmp/stderr"; fail=1; }
"$sph" -case lid_driven_cavity -isph_operators classic -nx 8 -max_steps 1 -progress 0 -output_dir $tmp/out -overwrite -ppe_ksp_type minres >/dev/null 2>"$tmp/stderr"
grep -q "warning: -ppe_ksp_type minres assumes a symmetric matrix" "$tmp/stderr" && echo "ok: minres in the walled cavity warned against" \
  || { echo "FAIL: no minres warning with walls:"; cat "$tmp/stderr"; fail=1; }
expect_ok $small -ppe_ksp_type preonly -ppe_pc_type lu
expect_ok $small -isph_operators classic -ppe_ksp_type cg

# PETSc options read late (a solve's viewers, -log_view at the end) are accepted, and act.
"$sph" $small -t_end 1 -max_steps 2 -output_dir "$tmp/late" -ppe_ksp_converged_reason -ppe_pc_view -log_view :"$tmp/log.txt" \
  >"$tmp/stdout" 2>"$tmp/stderr" || { echo "FAIL: late-read PETSc options refused:"; cat "$tmp/stderr"; fail=1; }
# Two steps, two solves each (the projection and its correction pass).
[ "$(grep -c "Linear ppe_ solve converged" "$tmp/stdout")" -eq 4 ] || { echo "FAIL: -ppe_ksp_converged_reason not once per solve"; fail=1; }
# -ppe_pc_view: once per solve.
[ "$(grep -c "^PC Object: (ppe_)" "$tmp/stdout")" -eq 4 ] || { echo "FAIL: -ppe_pc_view not once per solve"; fail=1; }
# Each solve is named before PETSc's lines about it: projection, then correction, every step (the
# names are PETSc's own, with the prefix: "Linear ppe_ solve converged").
[ "$(grep -E "^PPE (projection|correction) solve$|Linear ppe_ solve converged" "$tmp/stdout" | sed 's/ due to.*//' | tr '\n' '|')" = \
  "$(printf 'PPE projection solve|Linear ppe_ solve converged|PPE correction solve|Linear ppe_ solve converged|%.0s' 1 2)" ] \
  || { echo "FAIL: the solves are not named before their -ppe_ksp_converged_reason lines:"; cat "$tmp/stdout"; fail=1; }
grep -q "SPH time loop" "$tmp/log.txt" || { echo "FAIL: -log_view wrote no log"; fail=1; }
[ -s "$tmp/stderr" ] && { echo "FAIL: warnings from a run with late-read options:"; cat "$tmp/stderr"; fail=1; }

# -help: exit 0, documents case, solver, driver and PETSc KSP options with defaults.
"$sph" -help >"$tmp/help" 2>&1 || { echo "FAIL: -help exited non-zero"; fail=1; }
for opt in -case -solver -nx -re -t_end -cfl -shifting -kernel -output_dir -ppe_ksp_type -ppe_pc_type; do
  grep -q -- "$opt" "$tmp/help" || { echo "FAIL: -help does not list $opt"; fail=1; }
done

# -help opens with the essential options, each of them one that an options block documents below it
# (-options_file is PETSc's own, read at start-up).
head -1 "$tmp/help" | grep -q "Essential options" || { echo "FAIL: -help does not open with the essential options"; fail=1; }
essential=$(sed -n '/Essential options/,/^$/p' "$tmp/help" | grep -oE '^  (-[a-z_]+)(, -[a-z_]+)*' | tr ',' '\n' | tr -d ' ')
[ "$(echo "$essential" | wc -l)" -ge 10 ] || { echo "FAIL: the essential section lists too few options: $essential"; fail=1; }
for opt in $essential; do
  [ "$opt" = -options_file ] && continue
  grep -qE -- "^  $opt <" "$tmp/help" || { echo "FAIL: essential option $opt is not documented by any options block"; fail=1; }
done
# The other options are standard, or expert ("(expert)" opens the help line): none is both essential
# and expert.
for opt in $essential; do
  grep -E -- "^  $opt[ :]" "$tmp/help" | grep -q "(expert)" && { echo "FAIL: essential option $opt is marked expert"; fail=1; }
done
grep -qE -- "^  -projection_corrections <.*>: \(expert\) " "$tmp/help" \
  || { echo "FAIL: -projection_corrections is not marked expert"; fail=1; }

# A case file loads and the command line overrides it.
"$sph" -options_file "$src/cases/taylor_green.opts" -nx 8 -t_end 0.01 -progress 0 -output_dir "$tmp/tg" \
  >/dev/null 2>"$tmp/stderr" || { echo "FAIL: case file run"; cat "$tmp/stderr"; fail=1; }
grep -q '"nx": 8' "$tmp/tg/summary.json" || { echo "FAIL: -nx did not override the case file"; fail=1; }
exit $fail
