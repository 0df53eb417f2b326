#!/usr/bin/env bash
# Compile time of cellforge's headers as ratios to a translation unit of standard headers
# only (<vector> <string> <algorithm> <unordered_map> <span> <ranges>), compiled in the same
# run: each TU includes one header (or a set) and makes one call, built with
# `$CXX -std=c++20 -O0 -c`, the median of CELLFORGE_COMPILE_RUNS runs (default 5) of each.
# Prints one row per TU: median seconds, ratio to the baseline, peak memory (MB).
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

# name|includes|body of main
cases=(
  "baseline (standard headers)|${std_headers}|std::vector<int> v{3, 1, 2}; std::ranges::sort(v); return v[0];"
  "halfedge/mesh.hpp|#include \"cellforge/halfedge/mesh.hpp\"|cellforge::halfedge_mesh m; m.add_vertices(3); return static_cast<int>(m.num_vertices());"
  "halfedge/surface_mesh.hpp|#include \"cellforge/halfedge/surface_mesh.hpp\"
#include <glm/vec3.hpp>|cellforge::surface_mesh<glm::dvec3> m; m.add_vertex({1, 2, 3}); return static_cast<int>(m.num_vertices());"
  "cellforge.hpp|#include \"cellforge/cellforge.hpp\"|cellforge::halfedge_mesh m; return static_cast<int>(m.num_vertices());"
  "cellforge.hpp + io|#include \"cellforge/cellforge.hpp\"
#include \"cellforge/io/cells_io.hpp\"
#include \"cellforge/io/curves_io.hpp\"
#include \"cellforge/io/edge_list.hpp\"
#include \"cellforge/io/mesh_io.hpp\"
#include \"cellforge/io/svg.hpp\"|cellforge::halfedge_mesh m; return static_cast<int>(m.num_vertices());"
)

median() { sort -n | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }

printf '%-32s %9s %7s %8s\n' "translation unit ($cxx -O0)" "median s" "ratio" "peak MB"
base=""
for entry in "${cases[@]}"; do
  name="${entry%%|*}"
  rest="${entry#*|}"
  includes="${rest%|*}"
  body="${rest##*|}"
  tu="$work/tu.cpp"
  printf '%s\nint main() { %s }\n' "$includes" "$body" >"$tu"
  times=()
  mem=0
  for ((i = 0; i < runs; ++i)); do
    out="$({ /usr/bin/time -f '%e %M' "$cxx" -std=c++20 -O0 -I"$root/include" -c "$tu" -o "$work/tu.o"; } 2>&1 | tail -n 1)"
    times+=("${out% *}")
    kb="${out#* }"
    ((kb > mem)) && mem=$kb
  done
  t="$(printf '%s\n' "${times[@]}" | median)"
  [[ -z "$base" ]] && base="$t"
  printf '%-32s %9.2f %6.2fx %8d\n' "$name" "$t" "$(echo "$t / $base" | bc -l)" "$((mem / 1024))"
done
