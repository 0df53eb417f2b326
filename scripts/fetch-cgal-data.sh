#!/usr/bin/env bash
# Puts CGAL's demo meshes where the real-mesh sweep (tests/test_real_meshes.cpp) looks for them:
#   bash scripts/fetch-cgal-data.sh [<dir>]        (default: build/data)
# makes sure Debian's libcgal-demo is installed (it ships /usr/share/doc/libcgal-dev/data.tar.gz;
# apt-get runs only when the package is missing, through sudo only when not root) and unpacks
# every mesh file of the archive's data/meshes (OFF, PLY, STL, OBJ: 138 OFF, 3 PLY, 2 STL in
# CGAL 5.5, 46 MB) into <dir>/cgal/. Skipped when <dir>/cgal/ holds as many meshes as the archive,
# so a second run needs neither network nor apt. Configure and build never call this: it runs as a
# separate step (scripts/test-all.sh does it once before its stages).
set -euo pipefail

dir="${1:-build/data}"
out="$dir/cgal"
archive=/usr/share/doc/libcgal-dev/data.tar.gz
pattern='^data/meshes/[^/]*\.([oO][fF][fF]|[pP][lL][yY]|[sS][tT][lL]|[oO][bB][jJ])$'

if [[ ! -s "$archive" ]]; then
  echo "fetch-cgal-data.sh: installing libcgal-demo"
  bash "$(dirname "${BASH_SOURCE[0]}")/install-deps.sh" --only libcgal-demo
  [[ -s "$archive" ]] || { echo "fetch-cgal-data.sh: no $archive: install CGAL's demo data (Debian: libcgal-demo)" >&2; exit 1; }
fi

mapfile -t members < <(tar -tzf "$archive" | grep -E "$pattern")
if ((${#members[@]} == 0)); then
  echo "fetch-cgal-data.sh: $archive holds no mesh under data/meshes" >&2
  exit 1
fi
have=0
if [[ -d "$out" ]]; then
  for m in "${members[@]}"; do [[ -s "$out/$(basename "$m")" ]] && have=$((have + 1)); done
fi
if ((have == ${#members[@]})); then
  echo "fetch-cgal-data.sh: $out holds all ${#members[@]} meshes"
  exit 0
fi

# Unpacked beside the target first and moved in whole, so an interrupted run never leaves a
# truncated mesh behind for the sweep to report as a failure of the pipeline.
mkdir -p "$dir"
tmp="$(mktemp -d "$dir/cgal.tmp.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
tar -xzf "$archive" -C "$tmp" "${members[@]}"
mkdir -p "$out"
for m in "${members[@]}"; do mv -f "$tmp/$m" "$out/"; done
echo "fetch-cgal-data.sh: wrote ${#members[@]} meshes to $out ($(du -sh "$out" | cut -f1))"
