#!/usr/bin/env bash
# Runs every libFuzzer target (tests/fuzz/fuzz_*.cpp) for N minutes each, one after another (or
# CELLFORGE_FUZZ_JOBS at once), beyond CI's seconds. Not run in CI.
#
#   scripts/fuzz-long.sh N [fuzzer name ...]     e.g. scripts/fuzz-long.sh 10, scripts/fuzz-long.sh 2 fuzz_swc
#
# Builds the `fuzz` preset (clang, build/fuzz), then runs each fuzzer with its seeds and
# dictionary; new inputs are kept in build/fuzz/long/<name>/corpus between runs, crashes,
# timeouts and out-of-memory inputs go to build/fuzz/long/<name>/. Prints one line per fuzzer
# (runs, new coverage, the reproducing command for anything found) and exits 1 when any found
# something. Turn a finding into a test: copy the input into tests/fuzz/corpus/<name>/ (the
# seed replay under ctest then runs it) and write the unit test that names the defect.
# Environment: CELLFORGE_FUZZ_JOBS (fuzzers at once, default 1: two cores are shared),
# CELLFORGE_FUZZ_RSS_MB (default 2048).
set -euo pipefail

if [[ $# -lt 1 || ! "$1" =~ ^[0-9]+([.][0-9]+)?$ ]]; then
  echo "usage: $0 MINUTES [fuzzer name ...]" >&2
  exit 2
fi
minutes="$1"
shift
seconds=$(awk -v m="$minutes" 'BEGIN { printf "%d", m * 60 }')
jobs="${CELLFORGE_FUZZ_JOBS:-1}"
rss="${CELLFORGE_FUZZ_RSS_MB:-2048}"
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"

wanted=("$@")
nice cmake --preset fuzz >/dev/null
if [[ ${#wanted[@]} -eq 0 ]]; then
  nice cmake --build --preset fuzz
else  # only the fuzzers asked for
  nice cmake --build --preset fuzz --target "${wanted[@]}"
fi
list="build/fuzz/fuzzers.txt"
if [[ ! -s "$list" ]]; then
  echo "fuzz-long: $list lists no fuzzers" >&2
  exit 1
fi

# shellcheck source=scripts/fuzz-common.sh
source "$root/scripts/fuzz-common.sh"
fuzz_all "$list" "$root/build/fuzz/long" "$seconds" 20 "$rss" "$jobs" fuzz-long "${wanted[@]}"

failed=0
for dir in "${fuzz_dirs[@]}"; do
  name="$(basename "$dir")"
  runs=$(grep -m1 -o 'stat::number_of_executed_units: [0-9]*' "$dir/log" | grep -o '[0-9]*$' || echo '?')
  cov=$(grep -o 'cov: [0-9]*' "$dir/log" | tail -n 1 | grep -o '[0-9]*$' || echo '?')
  found=("$dir"/crash-* "$dir"/timeout-* "$dir"/oom-* "$dir"/leak-* "$dir"/slow-unit-*)
  any=0
  for a in "${found[@]}"; do [[ -e "$a" ]] && any=1; done
  if [[ "$(cat "$dir/status" 2>/dev/null)" == ok && $any -eq 0 ]]; then
    echo "fuzz-long: $name: nothing found in ${minutes} min ($runs runs, coverage $cov)"
  else
    failed=1
    echo "fuzz-long: $name FOUND something ($(cat "$dir/status" 2>/dev/null || echo 'no status'), $runs runs); last lines of $dir/log:" >&2
    tail -n 40 "$dir/log" >&2 || true
    for a in "${found[@]}"; do
      [[ -e "$a" ]] && echo "fuzz-long: reproduce with: build/fuzz/tests/fuzz/$name $a" >&2
    done
  fi
done
exit "$failed"
