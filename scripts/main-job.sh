#!/usr/bin/env bash
# The main job: installs what is missing, builds the main example in Release (build/main-job)
# and runs it on its bundled input with `-o out/`: its output files (e.g. the SVG picture) land in
# out/ at the top of the repository, whatever the current directory.
set -euo pipefail

# The example program that is "the main job"; examples/<name>.cpp builds target <name>.
main_example="wire2cells"

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

if [[ ! -f "examples/$main_example.cpp" ]]; then
  echo "main-job: the main example examples/$main_example.cpp does not exist (yet)," >&2
  echo "main-job: so there is no target '$main_example' to build; set main_example in $0" >&2
  exit 1
fi

if [[ "${CELLFORGE_SKIP_DEPS:-0}" != 1 ]]; then
  bash "$root/scripts/install-deps.sh"
fi

# Its own tree without the tests: in a tree with them the examples wait for the unity test groups.
cmake --preset ci -B "$root/build/main-job" -DCELLFORGE_BUILD_TESTS=OFF
cmake --build "$root/build/main-job" -j2 --target "$main_example"

exe="$root/build/main-job/examples/$main_example"
out="$root/out"
mkdir -p "$out"
stamp="$root/build/main-job/.main-job-stamp"
touch "$stamp"
sleep 1 # so that files written by the run are strictly newer than the stamp
echo "main-job: running $main_example -o $out"
echo
"$exe" -o "$out"
echo
echo "main-job: done; files written to $out:"
find "$out" -maxdepth 1 -type f -newer "$stamp" -printf '  %f (%s bytes)\n' | sort
