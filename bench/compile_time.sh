#!/usr/bin/env bash
# Compile time of cellforge's headers as ratios to a translation unit of standard headers
# only (<vector> <string> <algorithm> <unordered_map> <span> <ranges>), compiled in the same
# run: each TU includes one header (or a set) and makes one call, built with
# `$CXX -std=c++20 -O0 -c`. The TUs are compiled in interleaved rounds (every TU once per
# round, CELLFORGE_COMPILE_RUNS rounds, default 5), so that a change of load on a shared
# machine falls on all of them alike; each row prints the median wall seconds and the median
# user CPU seconds with their ratios to its baseline, and the peak memory (MB). Rows after one
# named "=..." are ratios to that row (the Eigen-only file for the Eigen headers).
# CELLFORGE_COMPILE_ONLY=regex keeps the rows whose name matches (and their baselines).
# Usage: bash bench/compile_time.sh [compiler]   (default: g++)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cxx="${1:-${CXX:-g++}}"
runs="${CELLFORGE_COMPILE_RUNS:-5}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

std_headers='#include <algorithm>
#include <ranges>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>'

umbrella_and_io='#include "cellforge/cellforge.hpp"
#include "cellforge/io/cells_io.hpp"
#include "cellforge/io/curves_io.hpp"
#include "cellforge/io/edge_list.hpp"
#include "cellforge/io/mesh_io.hpp"
#include "cellforge/io/svg.hpp"'
one_call='cellforge::halfedge_mesh m; return static_cast<int>(m.num_vertices());'

# The line-drawing rows: the drawing io and find_faces against the standard-headers baseline;
# drawing_to_cells with cellforge/sketch.hpp against an Eigen-only file (Dense and Sparse, one
# QR), each header-only and with CELLFORGE_EXTERN_SKETCH (the engines compiled once elsewhere,
# by cellforge/sketch/instantiate.hpp: docs/sketch.md, "Compile time").
eigen_dir="${CELLFORGE_EIGEN_INCLUDE:-/usr/include/eigen3}"
find_faces_tu='#include "cellforge/io/drawing_text.hpp"
#include "cellforge/sketch/face_finder.hpp"'
find_faces_call='const auto d = cellforge::io::read_drawing_text("in.txt"); return static_cast<int>(cellforge::find_faces(d).loops.size());'
d2c_tu='#include <glm/vec2.hpp>
#include "cellforge/sketch.hpp"'
d2c_call='cellforge::line_drawing<glm::dvec2> d; return static_cast<int>(cellforge::drawing_to_cells(d).faces.loops.size());'

# name|includes|body of main; a row whose name starts with "=" is a new baseline for the rows
# below it (their ratio column is to it)
cases=(
  "baseline (standard headers)|${std_headers}|std::vector<int> v{3, 1, 2}; std::ranges::sort(v); return v[0];"
  "halfedge/mesh.hpp|#include \"cellforge/halfedge/mesh.hpp\"|cellforge::halfedge_mesh m; m.add_vertices(3); return static_cast<int>(m.num_vertices());"
  "halfedge/surface_mesh.hpp|#include \"cellforge/halfedge/surface_mesh.hpp\"
#include <glm/vec3.hpp>|cellforge::surface_mesh<glm::dvec3> m; m.add_vertex({1, 2, 3}); return static_cast<int>(m.num_vertices());"
  "cellforge.hpp|#include \"cellforge/cellforge.hpp\"|${one_call}"
  "cellforge.hpp + io|${umbrella_and_io}|${one_call}"
  "+ io + sketch (non-Eigen)|${umbrella_and_io}
#include \"cellforge/sketch/arc_pairing.hpp\"
#include \"cellforge/sketch/elliptical_arc.hpp\"
#include \"cellforge/sketch/face_finder.hpp\"
#include \"cellforge/sketch/line_drawing.hpp\"
#include \"cellforge/sketch/round_skeleton.hpp\"|${one_call}"
  "find_faces + drawing io|${find_faces_tu}|${find_faces_call}"
  "the same, extern sketch|#define CELLFORGE_EXTERN_SKETCH
${find_faces_tu}|${find_faces_call}"
  "=Eigen Dense+Sparse, one QR|#include <Eigen/Dense>
#include <Eigen/Sparse>|Eigen::MatrixXd a = Eigen::MatrixXd::Random(4, 3); Eigen::VectorXd b = Eigen::VectorXd::Random(4); Eigen::VectorXd x = a.colPivHouseholderQr().solve(b); return x(0) > 0 ? 0 : 1;"
  "sketch.hpp: drawing_to_cells|${d2c_tu}|${d2c_call}"
  "the same, extern sketch|#define CELLFORGE_EXTERN_SKETCH
${d2c_tu}|${d2c_call}"
)

if [[ -n "${CELLFORGE_COMPILE_ONLY:-}" ]]; then
  kept=()
  for ((c = 0; c < ${#cases[@]}; ++c)); do
    name="${cases[$c]%%|*}"
    if ((c == 0)) || [[ "$name" == =* ]] || [[ "$name" =~ $CELLFORGE_COMPILE_ONLY ]]; then kept+=("${cases[$c]}"); fi
  done
  cases=("${kept[@]}")
fi

median() { sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }

count=${#cases[@]}
declare -a walls cpus mems
for ((c = 0; c < count; ++c)); do
  entry="${cases[$c]}"
  rest="${entry#*|}"
  printf '%s\nint main() { %s }\n' "${rest%|*}" "${rest##*|}" >"$work/tu$c.cpp"
  walls[$c]=""
  cpus[$c]=""
  mems[$c]=0
done
for ((i = 0; i < runs; ++i)); do
  for ((c = 0; c < count; ++c)); do
    out="$({ /usr/bin/time -f '%e %U %S %M' "$cxx" -std=c++20 -O0 -I"$root/include" -I"$eigen_dir" -c "$work/tu$c.cpp" -o "$work/tu.o"; } 2>&1 | tail -n 1)"
    read -r wall user sys kb <<<"$out"
    walls[$c]="${walls[$c]} $wall"
    cpus[$c]="${cpus[$c]} $user"
    ((kb > mems[$c])) && mems[$c]=$kb
  done
done

printf '%-32s %8s %7s %8s %7s %8s\n' "translation unit ($cxx -O0)" "wall s" "ratio" "user s" "ratio" "peak MB"
for ((c = 0; c < count; ++c)); do
  name="${cases[$c]%%|*}"
  w="$(printf '%s\n' ${walls[$c]} | median)"
  u="$(printf '%s\n' ${cpus[$c]} | median)"
  ((c == 0)) && base_w="$w" && base_u="$u"
  [[ "$name" == =* ]] && base_w="$w" && base_u="$u" && name="${name#=}"
  printf '%-32s %8.2f %6.2fx %8.2f %6.2fx %8d\n' "$name" "$w" "$(echo "$w / $base_w" | bc -l)" "$u" \
    "$(echo "$u / $base_u" | bc -l)" "$((mems[$c] / 1024))"
done
