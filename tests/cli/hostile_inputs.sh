#!/usr/bin/env bash
# Input that must not take the machine down or touch the user's files: -overwrite removes only what runs
# wrote (the folder's manifest), a run stopped before -t_end leaves a checkpoint to continue from, and
# malformed scenes, meshes and option values are refused in one line.   usage: hostile_inputs.sh <sph executable> <source dir>
set -u
sph="$1"; src="$2"; tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
fail=0
source "$(dirname "$0")/lib/expect.sh"
check() { if eval "$1"; then echo "ok: $2"; else echo "FAIL: $2"; fail=1; fi; }
small="-case taylor_green -nx 8 -progress 0 -threads 1"

# -overwrite removes the files the runs there wrote, and nothing else: not the user's table, backup or
# a file whose name looks like an output.
d="$tmp/run"
expect_ok $small -t_end 0.02 -output_dir "$d"
echo "user data" >"$d/my_measurements.csv"; cp "$d/checkpoint.bin" "$d/checkpoint.bin.bak"; echo "x" >"$d/body_mybody.pvd"
expect_ok $small -t_end 0.02 -output_dir "$d" -overwrite
check '[ -f "$d/my_measurements.csv" ] && [ -f "$d/checkpoint.bin.bak" ] && [ -f "$d/body_mybody.pvd" ]' \
  "-overwrite keeps the user's files beside the run"
check '[ -f "$d/summary.json" ] && grep -qx summary.json "$d/.sph_manifest"' "the new run lists its files in .sph_manifest"
# A folder whose results no manifest lists (an earlier version's run, or the user's files) is left alone.
o="$tmp/unlisted"; mkdir -p "$o"; echo "{}" >"$o/summary.json"; echo "mine" >"$o/notes.csv"
expect_error "holds results \(summary.json\) that no manifest of a run lists" $small -t_end 0.02 -output_dir "$o" -overwrite
check '[ -f "$o/notes.csv" ] && [ "$(cat "$o/summary.json")" = "{}" ]' "an unlisted folder is untouched by -overwrite"

# A run stopped by -max_steps before -t_end writes its checkpoint, says so, and -restart continues it.
m="$tmp/steps"
expect_ok $small -t_end 0.3 -output_interval 0 -max_steps 3 -output_dir "$m"
expect_json "$m/summary.json" "s['status'] == 'completed' and s['stopped_early']['reason'] == 'max_steps' and s['t_final'] < 0.3" \
  "-max_steps: summary.json says stopped_early"
expect_ok $small -t_end 0.3 -output_interval 0 -restart "$m/checkpoint.bin"
expect_json "$m/summary.json" "abs(s['t_final'] - 0.3) < 1e-12 and 'stopped_early' not in s and len(s['history']) == 2" \
  "-restart continues a run stopped by -max_steps to -t_end"

# A step so small that the run cannot end is refused at once, naming the option (it ran with an ETA of
# 1e27 s).
expect_error "the time step .* leaves .* steps to -t_end 0.3 \(more than 1e\+09\): -cfl is far too small; raise it" \
  $small -t_end 0.3 -cfl 1e-30 -output_dir "$tmp/tiny_cfl"
expect_error "-dt is far too small; raise it or leave it out" $small -t_end 0.3 -dt 1e-20 -output_dir "$tmp/tiny_dt"
# With the default Courant number, a step made tiny by a scene's velocity (metres given as microns a
# second) names the speed, not the Courant number.
printf 'dimension: 2\nbox: [-0.3, 1.3, -0.3, 1.3]\ngravity: [0, -1]\nregions:\n  - {role: wall, shape: difference, of: [{box: [-0.3, 1.3, -0.3, 1.3]}, {box: [0, 1, 0, 1]}]}\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.5], velocity: [1.0e8, 0]}\n' >"$tmp/fast.yaml"
for solver in isph wcsph; do
  expect_error "the flow's speed sets it \(the fastest particle moves at 1e\+08 against a spacing of 0.05\), far too fast .* check the initial velocities and their units" \
    -case scene -scene_file "$tmp/fast.yaml" -solver $solver -nx 20 -progress 0 -output_dir "$tmp/fast_$solver"
done

# An output folder that cannot be made is named with the reason (a read-only file system read as "No
# such file" when the lock file's open said it instead); here its parent is a file.
echo x >"$tmp/a_file"
expect_error "cannot create the output directory .*a_file/sub \(Not a directory\); choose a writable -output_dir" \
  $small -t_end 0.02 -output_dir "$tmp/a_file/sub"

# A YAML scene where nothing moves is told to add U: to its file, not "field data 'U'" (a .vtp term).
printf 'dimension: 2\nbox: [0, 1, 0, 1]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.5]}\n' >"$tmp/still.yaml"
expect_error "still.yaml': sets no reference speed and nothing moves \(no velocity, no gravity\); add U: \(a reference speed\) to the file or pass -U" -case scene -scene_file "$tmp/still.yaml" -nx 10 -output_dir "$tmp/u1"

# A restart from a scene edited since is refused naming the input, not an option that does not exist
# (-scene_checksum).
printf 'dimension: 2\nbox: [0, 1, 0, 1]\ngravity: [0, -1]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.5]}\n' >"$tmp/edited.yaml"
expect_ok -case scene -scene_file "$tmp/edited.yaml" -nx 10 -max_steps 2 -progress 0 -output_dir "$tmp/e1"
echo "# edited" >>"$tmp/edited.yaml"
expect_error "was written with scene_checksum = .*: the case's input changed since \(a scene file edited, or another version of sph\); restart with the input it was written from" -case scene -scene_file "$tmp/edited.yaml" -nx 10 -max_steps 4 -progress 0 -restart "$tmp/e1/checkpoint.bin"

# -checkpoints_kept is bounded (each kept one is a copy of the state), and an integer beyond the
# option's type is refused instead of wrapping.
expect_error "-checkpoints_kept must be between 1 and 1000" $small -t_end 0.02 -checkpoints_kept 100000000 -output_dir "$tmp/k1"
expect_error "option -checkpoints_kept has the value '2147483648', beyond the integers it takes" $small -t_end 0.02 -checkpoints_kept 2147483648 -output_dir "$tmp/k2"

# A mesh face naming a vertex the OBJ file does not hold (past the end, or 0: OBJ counts from 1) is
# refused naming the line, not read out of bounds.
printf 'v 0.3 0.3 0.2\nv 0.7 0.3 0.2\nv 0.5 0.7 0.2\nv 0.5 0.5 0.6\nf 1 2 3\nf 1 2 4\nf 2 3 4\nf 1 3 99\n' >"$tmp/far.obj"
sed 's/f 1 3 99/f 1 3 0/' "$tmp/far.obj" >"$tmp/zero.obj"
for m in far zero; do
  printf 'dimension: 3\nbox: [0, 1, 0, 1, 0, 1]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 1, 0, 1]}\n  - {role: body, name: tet, shape: mesh, file: %s.obj}\n' $m >"$tmp/$m.yaml"
done
expect_error "far.obj' line 8: a face names vertex 99 of the 4 the file holds" -case scene -scene_file "$tmp/far.yaml" -nx 10 -output_dir "$tmp/o1"
expect_error "zero.obj' line 8: a face names vertex 0; OBJ numbers vertices from 1" -case scene -scene_file "$tmp/zero.yaml" -nx 10 -output_dir "$tmp/o2"

# A YAML key given twice in one mapping is refused naming both lines, not settled by the first.
printf 'dimension: 2\nbox: [0, 1, 0, 1]\ndimension: 3\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.5]}\n' >"$tmp/twice.yaml"
expect_error "line 3: key 'dimension' is given a second time in one mapping \(first on line 1\); keep one" -case scene -scene_file "$tmp/twice.yaml" -nx 10 -output_dir "$tmp/o3"
printf 'dimension: 2\nbox: [0, 1, 0, 1]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.5], velocity: [1, 0], velocity: [0, 1]}\n' >"$tmp/twice2.yaml"
expect_error "line 4: key 'velocity' is given a second time" -case scene -scene_file "$tmp/twice2.yaml" -nx 10 -output_dir "$tmp/o4"
# Shapes nested deeper than the YAML reader takes are named as such, not as a syntax error.
python3 -c "print('dimension: 2\nbox: [0, 1, 0, 1]\nregions:\n  - {role: fluid, shape: ' + '{union: [' * 1000 +
  '{box: [0.1, 0.9, 0.1, 0.5]}' + ']}' * 1000 + '}')" >"$tmp/nested.yaml"
expect_error "line 5: nested [0-9]+ levels deep, deeper than the YAML reader takes; give a union's or a difference's shapes as one list" \
  -case scene -scene_file "$tmp/nested.yaml" -nx 10 -output_dir "$tmp/o-nested"

# The memory check comes before the particles exist: a YAML scene counts its lattice first, and a
# mesh drawn in millimetres for a scene in metres is refused naming the unit (not refined to dx/4 until
# the memory is gone). Both under a memory limit, so a regression cannot take the machine down.
python3 - "$tmp/cube_mm.stl" <<'PY'
import sys
lo, hi = (300.0, 300.0, 150.0), (700.0, 700.0, 550.0)
corner = lambda b: tuple(hi[a] if b >> a & 1 else lo[a] for a in range(3))
with open(sys.argv[1], "w") as f:
    f.write("solid cube\n")
    for q in [(0, 2, 6, 4), (1, 5, 7, 3), (0, 4, 5, 1), (2, 3, 7, 6), (0, 1, 3, 2), (4, 6, 7, 5)]:
        for tri in ((q[0], q[1], q[2]), (q[0], q[2], q[3])):
            f.write(" facet normal 0 0 0\n  outer loop\n" + "".join("   vertex %g %g %g\n" % corner(b) for b in tri) +
                    "  endloop\n endfacet\n")
    f.write("endsolid cube\n")
PY
printf 'dimension: 3\nbox: [-0.3, 1.3, -0.3, 1.3, -0.3, 1.3]\ngravity: [0, 0, -1]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 1, 0, 0.7]}\n  - {role: body, name: cube, shape: mesh, file: cube_mm.stl}\n' >"$tmp/mm.yaml"
(ulimit -v 2000000; expect_error "cube_mm.stl' spans 400, 250 times the scene's box \(1.6\); is it in millimetres\? scale it by 0.001" -case scene -scene_file "$tmp/mm.yaml" -nx 12 -output_dir "$tmp/o5"; exit $fail) || fail=1
(ulimit -v 2000000; expect_error "the scene needs more than [0-9]+ particles; .* lower -nx" -case scene -scene_file "$src/cases/scenes/falling_block.yaml" -nx 20000 -output_dir "$tmp/o6"; exit $fail) || fail=1

# An allocation that fails past the memory check (here a limit below the machine's) is reported as
# running out of memory, with the fix, not as an internal error.
(ulimit -v 1000000; expect_error "ran out of memory \(an allocation failed\): .* lower -nx|the scene needs more than" -case scene -scene_file "$src/cases/scenes/falling_block.yaml" -nx 2000 -max_steps 1 -output_dir "$tmp/o7"; exit $fail) || fail=1
# The same where the allocation fails on an OpenMP thread (the neighbour list of a 1D tube that the
# memory check lets through, under a lower limit): carried out of the threads, not an abort.
(ulimit -v 400000; OMP_NUM_THREADS=2 expect_error "ran out of memory \(an allocation failed\): .* lower -nx" -case sod -solver compressible -nx 100000 -t_end 1e-5 -output_dir "$tmp/o8"; exit $fail) || fail=1
# -options_file without its file name: one line, not PETSc's traceback.
expect_error "option -options_file was given without a file name; give the path of an options file" $small -options_file
expect_error "option -options_file was given without a file name" -options_file -case taylor_green

# Geometry that gets no particle, or has no area or volume, is refused naming the region: a body
# smaller than the spacing or outside the box, a fluid region beyond the box, three collinear
# vertices, a closed STL whose z are all equal.
scene2() { printf 'dimension: 2\nbox: [0, 1, 0, 1]\ngravity: [0, -1]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.5]}\n  - %s\n' "$2" >"$tmp/$1.yaml"; }
scene2 tiny "{role: body, name: tiny, shape: circle, centre: [0.5, 0.25], radius: 0.01}"
scene2 away "{role: body, name: away, shape: circle, centre: [3, 3], radius: 0.2}"
scene2 beyond "{role: fluid, shape: box, bounds: [2, 3, 0, 0.5]}"
scene2 line "{role: fluid, shape: polygon, vertices: [[0.1, 0.6], [0.2, 0.7], [0.3, 0.8]]}"
expect_error "regions\[1\]: is body 'tiny', which holds no particle at dx = 0.05" -case scene -scene_file "$tmp/tiny.yaml" -nx 20 -output_dir "$tmp/g1"
expect_error "regions\[1\]: is body 'away', which holds no particle" -case scene -scene_file "$tmp/away.yaml" -nx 20 -output_dir "$tmp/g2"
expect_error "regions\[1\]: is a fluid region that holds no particle" -case scene -scene_file "$tmp/beyond.yaml" -nx 20 -output_dir "$tmp/g3"
expect_error "regions\[1\].shape.polygon: encloses no area \(its vertices lie on one line\)" -case scene -scene_file "$tmp/line.yaml" -nx 20 -output_dir "$tmp/g4"
# A body whose thin parts fall between the lattice's rows keeps a fraction of its shape: refused when
# it holds under a quarter of what its area holds at dx^2 (a hub kept, five strips 0.8 dx thick lost).
strips=""; for y in 0.48 0.58 0.68 0.78 0.88; do strips="$strips, {box: [0.05, 0.95, $y, $(python3 -c "print(round($y + 0.04, 2))")]}"; done
printf 'dimension: 2\nbox: [0, 1, 0, 1]\ngravity: [0, -1]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.4]}\n  - {role: body, name: comb, shape: union, of: [{circle: {centre: [0.5, 0.7], radius: 0.12}}%s]}\n' "$strips" >"$tmp/comb.yaml"
expect_error "regions\[1\]: is body 'comb', which holds 16 particles at dx = 0.05, under a quarter of the 82 its area .* holds: parts of it thinner than the spacing are lost" -case scene -scene_file "$tmp/comb.yaml" -nx 20 -output_dir "$tmp/g6"
sed 's/vertex \([^ ]*\) \([^ ]*\) [^ ]*$/vertex \1 \2 0.3/' "$tmp/cube_mm.stl" | sed 's/\b300\b/0.3/g; s/\b700\b/0.7/g' >"$tmp/flat.stl"
printf 'dimension: 3\nbox: [0, 1, 0, 1, 0, 1]\ngravity: [0, 0, -1]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 1, 0, 0.6]}\n  - {role: body, name: plate, shape: mesh, file: flat.stl}\n' >"$tmp/flat.yaml"
expect_error "flat.stl' encloses no volume" -case scene -scene_file "$tmp/flat.yaml" -nx 10 -output_dir "$tmp/g5"

# A body whose prescribed motion rams it through a fixed wall and out of the box: warned of when it
# enters the wall (kept in summary.json), stopped when it leaves the box, in both schemes.
printf 'dimension: 2\nbox: [-0.3, 1.3, -0.3, 1.3]\ngravity: [0, -1]\nt_end: 1.5\nregions:\n  - {role: wall, shape: difference, of: [{box: [-0.3, 1.3, -0.3, 1.3]}, {box: [0, 1, 0, 1]}]}\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.5]}\n  - {role: body, name: ram, shape: box, bounds: [0.6, 0.8, 0.6, 0.8], motion: {type: constant, velocity: [1, 0]}}\n' >"$tmp/ram.yaml"
for solver in isph wcsph; do
  expect_error "body 'ram' left the box \[-0.3, 1.3, -0.3, 1.3\] at t = 0.5[0-9]*: its prescribed motion carries it out; enlarge the scene's box" \
    -case scene -scene_file "$tmp/ram.yaml" -solver $solver -nx 20 -progress 0 -output_dir "$tmp/ram_$solver"
  grep -q "^sph: warning: step [0-9]* (t = 0.2[0-9]*): body 'ram' has entered a fixed wall" "$tmp/stderr" || { echo "FAIL: $solver: no warning as the ram entered the wall"; fail=1; }
  expect_json "$tmp/ram_$solver/summary.json" "s['status'] == 'failed' and any('entered a fixed wall' in w for w in s['warnings'])" "$solver: the ram's warning in summary.json"
done

# A folder where a file belongs (the scene, a motion table) is named as a folder, not reported as a
# failed read ("basic_filebuf::underflow").
mkdir -p "$tmp/folder.yaml" "$tmp/table"
printf 'dimension: 2\nbox: [0, 1, 0, 1]\nregions:\n  - {role: fluid, shape: box, bounds: [0, 1, 0, 0.4]}\n  - {role: body, name: b, shape: circle, centre: [0.5, 0.7], radius: 0.15, motion: {type: table, file: table}}\n' >"$tmp/moving.yaml"
expect_error "scene file '$tmp/folder.yaml': is a folder, not a scene file; give -scene_file the path of a .vtp or .yaml file" -case scene -scene_file "$tmp/folder.yaml" -output_dir "$tmp/f1"
expect_error "regions\[1\].motion.file: '$tmp/table' is a folder, not a file; give the motion table" -case scene -scene_file "$tmp/moving.yaml" -nx 20 -output_dir "$tmp/f2"

# A .vtp scene's spacing (field data dx or -scene_dx) far from its particles' own would run with
# particles that never interact: refused naming the measured spacing. A 3-component 'kind' is named
# as such, not as missing.
"$src/scripts/make-scene" cavity --nx 12 -o "$tmp/cavity.vtp" >/dev/null || { echo "FAIL: make-scene cavity"; fail=1; }
for d in dx_tiny kind_3; do /usr/bin/python3 "$(dirname "$0")/lib/bad_scene.py" "$tmp/cavity.vtp" "$tmp/$d.vtp" $d || { echo "FAIL: bad_scene.py $d"; fail=1; }; done
vtp="-case scene -max_steps 2 -progress 0"
expect_error "dx_tiny.vtp': its particles lie 0.0833333 apart \(median nearest-neighbour distance\), but its field data dx 1e-06 says otherwise; set field data dx to 0.0833333" $vtp -scene_file "$tmp/dx_tiny.vtp" -output_dir "$tmp/v1"
expect_error "cavity.vtp': its particles lie 0.0833333 apart .*, but -scene_dx 0.04 is given; pass -scene_dx 0.0833333 or leave it out" $vtp -scene_file "$tmp/cavity.vtp" -scene_dx 0.04 -output_dir "$tmp/v2"
expect_ok $vtp -scene_file "$tmp/cavity.vtp" -output_dir "$tmp/v3"
# A list option with an empty or malformed component is refused naming the option (PETSc dropped the
# empty one, and named no option for 0,-1x).
expect_error "option -gravity has the value '0,,-1', whose component 2 is empty" $vtp -scene_file "$tmp/cavity.vtp" -gravity 0,,-1 -output_dir "$tmp/v5"
expect_error "option -gravity has the value '0,-1,', whose component 3 is empty" $vtp -scene_file "$tmp/cavity.vtp" -gravity 0,-1, -output_dir "$tmp/v6"
expect_error "option -gravity has the value '0,-1x', whose component 2 \('-1x'\) is not a number" $vtp -scene_file "$tmp/cavity.vtp" -gravity 0,-1x -output_dir "$tmp/v7"
expect_ok $vtp -scene_file "$tmp/cavity.vtp" -gravity 0,-1e-3 -output_dir "$tmp/v8"
expect_error "kind_3.vtp': point array 'kind' has 3 components; give one" $vtp -scene_file "$tmp/kind_3.vtp" -output_dir "$tmp/v4"

# The help into a pipe closed early ends quietly, as any printing program does (SIGPIPE), without
# PETSc's crash report.
for k in 1 2 3 4 5; do
  "$sph" -help 2>"$tmp/help_err" | head -c 10 >/dev/null
  rc=${PIPESTATUS[0]}
  if [ -s "$tmp/help_err" ] || { [ "$rc" -ne 0 ] && [ "$rc" -ne 141 ]; }; then
    echo "FAIL: sph -help | head -c 10 -> exit $rc, stderr: $(head -3 "$tmp/help_err")"; fail=1; break
  fi
done
[ "$k" -eq 5 ] && [ "$fail" -eq 0 ] && echo "ok: sph -help | head -c 10 ends quietly (5 tries)"
exit $fail
