#!/usr/bin/env bash
# Runs every check cellforge has, as CI does:
#   1. ci       Release build (-O1, preset ci) of tests + examples, -Werror, then ctest   (build/ci)
#   2. asan     Debug build of the tests with ASan + UBSan and -Werror, then ctest (build/asan),
#               which also runs the header, README and clang-format checks (label "headers")
#   3. clang    every example and test compiled (syntax and templates) by clang with -Werror,
#               so that code g++ accepts but clang rejects does not land
#   4. bench    every benchmark configured in build/bench-check and compiled by g++ with
#               -fsyntax-only (templates instantiated, no code generated, not linked or run:
#               timings are not tests), so that benchmark code cannot rot; CGAL/OpenMesh/Qhull parts
#               only where they are installed
#   5. fuzz     libFuzzer targets built with clang, seed corpora replayed, then each fuzzer
#               run for CELLFORGE_FUZZ_SECONDS seconds (default 5)       (build/fuzz)
# Before the stages, scripts/fetch-bunny.sh puts the Stanford bunny (npm) in build/data, and
# scripts/fetch-cgal-data.sh CGAL's demo meshes (Debian's libcgal-demo) in build/data/cgal.
# Every stage runs even when an earlier one failed; the exit status is non-zero if any failed.
# The stages run in two lanes at once (ci, clang | asan, bench, fuzz; each line of output tagged
# with its stage): every stage has single-threaded parts (configuring, linking, the last tests
# of a ctest run, the clang stage's one big TU), and the other lane fills the idle core.
# Environment: CELLFORGE_FUZZ_SECONDS (default 5), CELLFORGE_FUZZ_JOBS (fuzzers run at once,
# default 2), CELLFORGE_SKIP_DEPS=1 to skip the package check, CELLFORGE_LANES=1 to run the
# stages one after another.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
fuzz_seconds="${CELLFORGE_FUZZ_SECONDS:-5}"
fuzz_jobs="${CELLFORGE_FUZZ_JOBS:-2}"

# Runs one preset end to end: configure, build, test.
preset_stage() {
  local preset="$1"
  cmake --preset "$preset"
  cmake --build --preset "$preset"
  ctest --preset "$preset" --output-on-failure -j2
}

fuzz_stage() {
  cmake --preset fuzz
  cmake --build --preset fuzz
  ctest --preset fuzz --output-on-failure -j2 # replays the seed corpora
  local list="build/fuzz/fuzzers.txt"
  if [[ ! -s "$list" ]]; then
    echo "test-all: $list lists no fuzzers" >&2
    return 1
  fi

  local name dir failed=0
  # shellcheck source=scripts/fuzz-common.sh
  source "$root/scripts/fuzz-common.sh"
  fuzz_all "$list" "$root/build/fuzz/runs" "$fuzz_seconds" 10 2048 "$fuzz_jobs" test-all

  for dir in "${fuzz_dirs[@]}"; do
    name="$(basename "$dir")"
    if [[ "$(cat "$dir/status" 2>/dev/null)" == ok ]]; then
      echo "test-all: $name: no crash in ${fuzz_seconds}s ($(grep -m1 -o 'stat::number_of_executed_units: [0-9]*' "$dir/log" | grep -o '[0-9]*$' || echo '?') runs)"
    else
      failed=1
      echo "test-all: $name FAILED ($(cat "$dir/status" 2>/dev/null || echo 'no status')); last lines of $dir/log:" >&2
      tail -n 60 "$dir/log" >&2 || true
      local artifacts=("$dir"/crash-* "$dir"/timeout-* "$dir"/oom-* "$dir"/leak-*)
      for a in "${artifacts[@]}"; do
        if [[ -e "$a" ]]; then echo "test-all: reproduce with: build/fuzz/tests/fuzz/$name $a" >&2; fi
      done
    fi
  done
  return "$failed"
}

# clang++ -fsyntax-only on every example, and on all test files as one translation unit (each
# file's body is in its own namespace, so they also must not clash): instantiates the
# templates they use, and parses the library's headers once for the tests instead of 38 times.
clang_stage() {
  local clang="${CXX_CLANG:-clang++}"
  command -v "$clang" >/dev/null || { echo "test-all: $clang not found" >&2; return 1; }
  # Eigen (the sketch solvers) as a system directory, as its CMake target gives it.
  local eigen
  eigen=$(pkg-config --cflags-only-I eigen3 2>/dev/null || echo "-I/usr/include/eigen3")
  eigen=${eigen%% *}
  local flags=(-std=c++20 -fsyntax-only -Wall -Wextra -Wpedantic -Werror -Iinclude -Itests
    "-isystem${eigen#-I}" '-DCELLFORGE_DATA_DIR=""' '-DCELLFORGE_TEST_DATA_DIR=""' '-DCELLFORGE_TEST_PROJECT_VERSION=""')
  mkdir -p build/clang
  local all=build/clang/all_tests.cpp
  find "$root/tests" -maxdepth 1 -name 'test_*.cpp' | sort | sed 's|.*|#include "&"|' >"$all"
  local pids=() failed=0
  echo "clang: $(grep -c . "$all") test files as one translation unit"
  "$clang" "${flags[@]}" "$all" &
  pids+=($!)
  # Then sketch/instantiate.hpp with CELLFORGE_EXTERN_SKETCH (headers_alone leaves it out: 52 s).
  local inst=build/clang/instantiate.cpp
  printf '#define CELLFORGE_EXTERN_SKETCH\n#include "cellforge/sketch/instantiate.hpp"\n' >"$inst"
  {
    find examples -maxdepth 1 -name '*.cpp' -print0 | sort -z |
      xargs -0 -P 1 -I{} sh -c 'echo "clang: {}"; "$0" "$@" "{}"' "$clang" "${flags[@]}" &&
      echo "clang: sketch/instantiate.hpp" && "$clang" "${flags[@]}" "$inst"
  } &
  pids+=($!)
  for pid in "${pids[@]}"; do wait "$pid" || failed=1; done
  return "$failed"
}

bench_stage() {
  cmake --preset bench -B build/bench-check -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0
  local db=build/bench-check/compile_commands.json commands=build/bench-check/syntax-only.txt
  [[ -s "$db" ]] || { echo "test-all: $db is missing" >&2; return 1; }
  # One command a line: JSON's \\ and \" unescaped, the object output replaced by -fsyntax-only.
  # CELLFORGE_EXTERN_SKETCH: the line-drawing engines are declared, not instantiated again
  # (bench_sketch: 105 -> 44 CPU-s with g++); the ci stage's engines object compiles them with g++.
  grep -o '"command": ".*"' "$db" | sed -e 's/^"command": "//' -e 's/"$//' -e 's/\\\\/\x01/g' -e 's/\\"/"/g' -e 's/\x01/\\/g' \
    -e 's/ -o [^ ]* -c / -DCELLFORGE_EXTERN_SKETCH -fsyntax-only /' >"$commands"
  [[ -s "$commands" ]] || { echo "test-all: no compile commands in $db" >&2; return 1; }
  echo "bench: $(wc -l <"$commands") benchmark files, -fsyntax-only"
  sed 's|.* ||' "$commands"  # the files, for the log
  xargs -d '\n' -P 2 -I{} sh -c '{}' <"$commands"
}

if [[ "${1:-}" == "--stage" ]]; then
  case "${2:-}" in
    ci | asan) preset_stage "$2" ;;
    release) preset_stage ci ;; # the stage's name before 0.6
    fuzz) fuzz_stage ;;
    clang) clang_stage ;;
    # Only whether the benchmarks compile matters here (timings are never taken in CI): each
    # compile command of the configured tree runs with -fsyntax-only instead of writing an
    # object (half the time of an -O0 build), in its own directory: build/bench stays a
    # Release tree for real runs.
    bench) bench_stage ;;
    *)
      echo "test-all: unknown stage '${2:-}'" >&2
      exit 2
      ;;
  esac
  exit 0
fi

start=$SECONDS
if [[ "${CELLFORGE_SKIP_DEPS:-0}" != 1 ]]; then
  bash "$root/scripts/install-deps.sh" --bench --fuzz --occt
fi

stages=(ci asan clang bench)
if compgen -G "$root/tests/fuzz/fuzz_*.cpp" >/dev/null; then
  stages+=(fuzz)
else
  echo "test-all: no tests/fuzz/fuzz_*.cpp sources, skipping the fuzz stage"
fi

passed=()
failed=()
# The Stanford bunny (npm package) for the thin-point test and benchmark, once, before the
# stages; the default CELLFORGE_BUNNY_FILE is build/data/bunny.off. Skipped when present.
if ! bash "$root/scripts/fetch-bunny.sh" "$root/build/data"; then
  failed+=("bunny-data")
  echo "=== test-all: fetching the bunny FAILED (bash scripts/fetch-bunny.sh build/data; needs node, npm and the npm registry); test_thin_bunny will fail under CI ===" >&2
fi
# CGAL's demo meshes for the real-mesh sweep (test_real_meshes), once, before the stages; the
# default CELLFORGE_REAL_MESH_DIR is build/data. Skipped when unpacked already.
if ! bash "$root/scripts/fetch-cgal-data.sh" "$root/build/data"; then
  failed+=("cgal-data")
  echo "=== test-all: fetching CGAL's demo meshes FAILED (bash scripts/fetch-cgal-data.sh build/data; needs libcgal-demo); test_real_meshes will fail under CI ===" >&2
fi
# Runs the stages given, one after another, each line of output tagged "[stage]"; appends
# "passed <stage> <seconds>" or "failed <stage> <seconds>" to the file $1.
run_lane() {
  local record="$1" stage stage_start status
  shift
  for stage in "$@"; do
    echo "=== test-all: stage '$stage' ==="
    stage_start=$SECONDS
    # A separate bash process, so that `set -e` stops the stage at its first failing command.
    status=0
    bash "$root/scripts/test-all.sh" --stage "$stage" 2>&1 | sed -u "s/^/[$stage] /" || status=$?
    if ((status == 0)); then
      echo "passed $stage $((SECONDS - stage_start))" >>"$record"
    else
      echo "failed $stage $((SECONDS - stage_start))" >>"$record"
      echo "=== test-all: stage '$stage' FAILED ===" >&2
    fi
  done
}

record="$(mktemp)"
trap 'rm -f "$record"' EXIT
lane_a=() lane_b=()
for stage in "${stages[@]}"; do
  case "$stage" in
    asan | bench | fuzz) lane_b+=("$stage") ;;
    *) lane_a+=("$stage") ;;
  esac
done
if [[ "${CELLFORGE_LANES:-2}" == 1 ]]; then
  run_lane "$record" "${stages[@]}"
else
  run_lane "$record" "${lane_a[@]}" &
  lane_pid=$!
  run_lane "$record" "${lane_b[@]}"
  wait "$lane_pid" || true
fi
while read -r verdict stage seconds; do
  if [[ "$verdict" == passed ]]; then
    passed+=("$stage (${seconds}s)")
  else
    failed+=("$stage (${seconds}s)")
  fi
done <"$record"

elapsed=$((SECONDS - start))
echo
if ((${#failed[@]} == 0)); then
  echo "test-all: PASSED: ${passed[*]}; total $((elapsed / 60))m$((elapsed % 60))s"
else
  echo "test-all: FAILED: ${failed[*]}; passed: ${passed[*]-none}; total $((elapsed / 60))m$((elapsed % 60))s" >&2
  exit 1
fi
