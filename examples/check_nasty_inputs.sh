#!/usr/bin/env bash
# Nasty inputs through the example programs: check_nasty_inputs.sh BIN_DIR WORK_DIR [--small].
# Writes each input (examples/nasty_inputs_gen.sh), runs the programs on it with a time limit
# and ASan's memory cap, and checks every run: it ended by itself (no signal, no time-out, no
# sanitizer report), with the exit status and the message that say what the input is.
# --small leaves out the big inputs (sanitizer builds). Prints one line per run and totals.
set -uo pipefail
bin="$1"
work="$2"
small="${3:-}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$work"
mkdir -p "$work"
bash "$here/nasty_inputs_gen.sh" "$work/in" || { echo "could not write the inputs"; exit 1; }
mkfifo "$work/in/fifo.obj"
export ASAN_OPTIONS="${ASAN_OPTIONS:-}:hard_rss_limit_mb=3000:detect_leaks=0"
runs=0
bad=0
# case EXE INPUT STATUS PATTERN [ARGUMENT...]: STATUS 0 (success), "error" (exit 1-3) or 4 (read,
# but not what the program needs, or no good result from it); PATTERN an extended regex the program's stderr (errors),
# stdout (success) or either (4) must match. With the
# argument --no-svg the run must write no .svg file. A non-empty $memory_kb caps the run's
# address space (ulimit -v; not in sanitizer builds, whose shadow memory needs terabytes of it).
memory_kb=""
case_() {
  local exe="$1" input="$2" want="$3" pattern="$4"
  shift 4
  local dir="$work/run/$exe-$(basename "$input")${1:+-$(echo "$*" | tr -c 'a-zA-Z0-9.\n' _)}"
  mkdir -p "$dir"
  runs=$((runs + 1))
  (cd "$dir" && { [[ -z "$memory_kb" ]] || ulimit -v "$memory_kb"; } &&
    timeout 120 "$bin/$exe" "$input" "$@" >"$dir/stdout.txt" 2>"$dir/stderr.txt" </dev/null)
  local rc=$?
  local why=""
  if grep -qE "AddressSanitizer|runtime error:|LeakSanitizer" "$dir/stderr.txt"; then why="sanitizer report"
  elif ((rc == 124)); then why="time-out (hang)"
  elif ((rc > 4)); then why="exit status $rc (crash or abort)"
  elif [[ "$want" == 0 && $rc != 0 ]]; then why="exit status $rc, expected success"
  elif [[ "$want" == 4 && $rc != 4 ]]; then why="exit status $rc, expected 4 (not for this program)"
  elif [[ "$want" == error ]] && ((rc == 0 || rc == 4)); then why="exit status $rc, expected an error"
  elif [[ "$want" == 0 ]] && ! grep -qE -- "$pattern" "$dir/stdout.txt"; then why="output lacks /$pattern/"
  elif [[ "$want" == 4 ]] && ! grep -qE -- "$pattern" "$dir/stdout.txt" "$dir/stderr.txt"; then
    why="output lacks /$pattern/"
  elif [[ "$want" == error ]] && ! grep -qE -- "$pattern" "$dir/stderr.txt"; then why="message lacks /$pattern/"
  elif [[ " $* " == *" --no-svg "* ]] && [[ -n "$(find "$dir" -name '*.svg' -print -quit)" ]]; then
    why="--no-svg, yet a picture was written"
  fi
  if [[ -n "$why" ]]; then
    bad=$((bad + 1))
    echo "MISS $exe $(basename "$input") $*: $why"
    tail -n 3 "$dir/stderr.txt" | sed 's/^/    /'
  else
    echo "ok   $exe $(basename "$input") $*"
  fi
}
i="$work/in"
w=wire2cells
case_ $w "$i/binary_garbage.obj" error "binary_garbage.obj:1: not an OBJ statement"
case_ $w "$i/comment_only.obj" error "no edges"
case_ $w "$i/empty.obj" error "no edges"
case_ $w "$i/points_only.obj" error "no edges"
case_ $w "$i/cube_wire.obj" 0 "8 vertices, 12 edges, 6 faces, 1 volumes"
case_ $w "$i/cube_mesh.obj" 0 "8 vertices, 12 edges, 6 faces, 1 volumes"
case_ $w "$i/CUBE_UPPER.OBJ" 0 "6 faces, 1 volumes"
case_ $w "$i/cube_1e-12.obj" 0 "6 faces, 1 volumes"
case_ $w "$i/cube_1e12.obj" 0 "6 faces, 1 volumes"
case_ $w "$i/cube_far.obj" 0 "6 faces, 1 volumes"
case_ $w "$i/cube_1e-300.obj" error "spans 1e-300 .*scale the model"
case_ $w "$i/cube_1e300.obj" error "spans 1e\\+300 .*scale the model"
case_ $w "$i/lone_square.obj" 4 "1 faces, 0 volumes"
case_ $w "$i/cube_missing_edge.obj" 4 "an open surface: 6 edges lie on one face only"
case_ $w "$i/cube_crossing_diagonals.obj" 4 "input edges 12, 13 lie on a cycle of the wireframe but on no face"
case_ $w "$i/face_index_out_of_range.obj" error "face_index_out_of_range.obj:15: face index 99 out of range"
case_ $w "$i/line_index_out_of_range.obj" error "line_index_out_of_range.obj:21: line index 99 out of range"
case_ $w "$i/nan.obj" error "nan.obj:1: coordinate z 'nan' is not finite"
case_ $w "$i/overflow_coordinate.obj" error "overflow_coordinate.obj:1: coordinate z '1e400' is out of range"
case_ $w "$i/self_loop.obj" error "self_loop.obj:4: line segment from vertex 1 to itself"
case_ $w "$i/short_vertex.obj" error "short_vertex.obj:1: expected coordinate z"
case_ $w "$i/huge_count.edges" error "huge_count.edges:1: the vertex count 99999999999 exceeds the 32-bit limit"
case_ $w "$i/negative_count.edges" error "negative_count.edges:1: the vertex count must not be negative"
case_ $w "$i/truncated.edges" error "truncated.edges:3: expected vertex 2 of 3, found end of file"
case_ $w "$i/fifo.obj" error "fifo.obj': not a regular file"
case_ $w /dev/zero error "'/dev/zero': not a regular file"
case_ $w "$i/k7.obj" 4 "read, but not a closed solid: "
case_ $w "$i/prism_1000.obj" 0 "2000 vertices, 3000 edges, 1002 faces, 1 volumes"
if [[ "$small" != --small ]]; then
  case_ $w "$i/k12.obj" 4 "read, but not a closed solid: input edges"
  case_ $w "$i/dup_1e5.obj" 0 "6 faces, 1 volumes"
  case_ $w "$i/cubes_4096.obj" 0 "24576 faces, 4096 volumes"
fi
for exe in mesh_info hull subdivide thin_points smooth_edges; do
  case_ $exe "$i/empty.off" error "empty.off:1: empty file"
  case_ $exe "$i/bad_header.ply" error "bad_header.ply:3: element 'vertex' has no property 'y'"
  case_ $exe "$i/truncated.stl" error "truncated.stl:4: facet 0: expected 'vertex', found end of file"
  case_ $exe "$i/all_degenerate.stl" error "all_degenerate.stl: all 1 facets are degenerate"
  case_ $exe "$i/binary_garbage.obj" error "binary_garbage.obj:1: not an OBJ statement"
  case_ $exe /dev/zero error "/dev/zero"
done
for exe in mesh_info hull subdivide; do
  case_ $exe "$i/open_square.off" 0 "."
  case_ $exe "$i/folded_sheet.off" 0 "."
  case_ $exe "$i/degenerate_triangle.off" 0 "."
  case_ $exe "$i/tetra.off" 0 "."
  case_ $exe "$i/cube_mesh.obj" 0 "."
  case_ $exe "$i/prism_1000.off" 0 "."
done
# Points without faces: the hull's input, not a mesh (exit 4, naming hull); a wireframe OBJ is
# no mesh either (naming wire2cells).
case_ hull "$i/coplanar_20000.off" 0 "."
for exe in mesh_info subdivide; do
  case_ $exe "$i/coplanar_20000.off" 4 "20000 points and no faces, not a mesh.*hull takes a point set"
  case_ $exe "$i/cube_wire.obj" 4 "is a wireframe OBJ \\(8 vertices, 12 lines, no faces\\).*wire2cells takes"
done
for exe in thin_points smooth_edges; do
  case_ $exe "$i/open_square.off" 4 "an open mesh \\(4 boundary edges\\), not a closed mesh"
  case_ $exe "$i/folded_sheet.off" error "encloses no volume"
  case_ $exe "$i/coplanar_20000.off" 4 "a mesh with no faces"
  case_ $exe "$i/cube_wire.obj" 4 "is a wireframe OBJ.*wire2cells takes"
  case_ $exe "$i/tetra.off" 0 "."
  case_ $exe "$i/cube_mesh.obj" 0 "."
  case_ $exe "$i/truncated.3dcl" error "truncated.3dcl:3: expected 'edges <count>'"
  case_ $exe "$i/loop_edge.3dcl" error "loop_edge.3dcl:6: make_cell_complex: edge 0 joins vertex 0 to itself"
done
case_ thin_points "$i/prism_1000.off" 0 "."
case_ tubes "$i/coincident_nodes.swc" error "nodes 0 and 1 coincide"
case_ tubes "$i/missing_parent.swc" error "missing_parent.swc:2: the parent 5 of sample 2 is not in the file"
case_ tubes "$i/parent_cycle.swc" error "parent_cycle.swc:1: the parents form a cycle"
case_ tubes "$i/zero_radius.swc" error "zero_radius.swc:3: the radius of sample 3, '0', must be positive"
case_ tubes /dev/zero error "give an .swc or .obj skeleton"
case_ tubes "$i/empty.swc" error "empty.swc': the skeleton has no nodes"
case_ tubes "$i/short_edge_turn.swc" 0 "1 path nodes merged with a neighbour" --sides 6 --no-svg
case_ tubes "$i/short_edge_turn.swc" 0 "^folds +0 edges" --no-svg
case_ tubes "$here/data/vessel_tree.swc" 4 "ran out of its budget" --check-pairs 1 --no-svg
case_ tubes "$i/cube_mesh.obj" 4 "is a mesh OBJ .*, not a skeleton"
case_ tubes "$i/cube_wire.obj" 4 "is a wireframe OBJ .*, no radii.*--radius"
case_ tubes "$i/cube_wire.obj" 0 "8 nodes, 12 edges" --radius 0.1 --no-svg
case_ sketch2cells "$i/empty.svg" error "the drawing has no edge"
case_ sketch2cells "$i/not_xml.svg" error "not_xml.svg:2: no <svg> element"
case_ sketch2cells "$i/unclosed.svg" error "unclosed.svg:2: the file ends inside <svg>"
case_ sketch2cells /dev/zero error "/dev/zero"
case_ sketch2cells "$here/data/l_bracket_rounds.txt" 4 "a drawing with arcs or curves, the first at line 42, not a drawing of straight lines.*sketch_rounds"
case_ sketch2cells "$here/data/l_bracket_rounds.dxf" 4 "a drawing with arcs or curves.*sketch_rounds"
case_ sketch2cells "$i/cube_mesh.obj" 4 "is a mesh OBJ .*mesh_info"
case_ sketch_rounds "$i/empty.svg" error "the drawing has no edge"
case_ sketch_rounds "$i/not_xml.svg" error "not_xml.svg:2: no <svg> element"
case_ sketch_rounds "$i/zero_radius_arc.txt" error "zero_radius_arc.txt:3: the radius rx of arc 0 .* is 0"
case_ sketch_rounds "$i/closed_arc.txt" error "closed_arc.txt:3: arc 0 starts and ends at junction 0"
case_ sketch_rounds "$i/lone_arc.txt" error "arc 0 \(junctions 2 to 0\) has no partner"
# The bundled L bracket with its fourth arc taken away: the message leads with the unpaired arc
# and names the skeleton's dangling junction in the drawing's numbering (it renumbers them).
awk '/^a / && ++arcs == 4 { next } { print }' "$here/data/l_bracket_rounds.txt" >"$i/l_bracket_lone_arc.txt"
case_ sketch_rounds "$i/l_bracket_lone_arc.txt" error "^sketch_rounds: reconstruct_rounds: arc 2 \(junctions 10 to 11\) has no partner.*skeleton junction 6 is junction 10 of the drawing"
case_ sketch_rounds "$i/circle.svg" error "circle.svg:1: .*<circle> is a closed curve"
case_ sketch_rounds /dev/zero error "/dev/zero"
case_ sketch_rounds "$here/data/l_bracket_rounds.txt" 0 "3 consistent, 0 inconsistent"
# Every program leaves its picture out when asked.
case_ $w "$i/cube_wire.obj" 0 "6 faces, 1 volumes" --no-svg
for exe in mesh_info hull subdivide thin_points smooth_edges; do
  case_ $exe "$i/cube_mesh.obj" 0 "." --no-svg
done
case_ tubes "$here/data/vessel_tree.swc" 0 "out/tubes.obj$" --no-svg
case_ sketch2cells "$here/data/stepped_normalon.svg" 0 "stepped_normalon.obj$" --no-svg
# The pictures of big flat scenes stay near-linear (they once took minutes).
if [[ "$small" != --small ]]; then
  case_ hull "$i/circle_20000.off" 0 "hull faces +39996"
  case_ subdivide "$i/twogons_20000.off" 0 "after +20000 vertices, 59994 edges, 39996 triangles" --levels 0
  case_ mesh_info "$i/twogons_20000.off" 0 "2 with 20000 sides"
fi
# Out of memory is a message naming what was being built and how big, not an abort. (Not in a
# sanitizer build: ASan reserves terabytes of address space and cannot start under ulimit -v.)
if [[ "$small" != --small ]] && ! grep -qa __asan_init "$bin/wire2cells"; then
  memory_kb=300000
  case_ subdivide "$i/tetra.off" error "out of memory while subdividing 4 faces 11 times \\(about 1.68e\\+07 faces\\)" --levels 11 --no-svg
  memory_kb=40000
  case_ $w "$i/cubes_4096.obj" error "out of memory while .*(32768 points and 49152 edges|24576 faces)"
  memory_kb=""
fi
echo "nasty inputs: $runs runs, $((runs - bad)) as expected, $bad misses"
((bad == 0))
