# shellcheck shell=bash
# Running the libFuzzer targets listed in build/fuzz/fuzzers.txt (one "exe|seeds|dict" a line),
# sourced by scripts/test-all.sh (seconds each, in CI's way) and scripts/fuzz-long.sh (minutes).

# fuzz_one EXE SEEDS DICT DIR SECONDS TIMEOUT RSS_MB: runs one fuzzer niced, never fails itself,
# and writes "ok" or the exit code to DIR/status. New inputs go to DIR/corpus (kept between
# runs), the seeds are read only, findings land in DIR/.
fuzz_one() {
  local exe="$1" seeds="$2" dict="$3" dir="$4"
  local args=(-max_total_time="$5" -timeout="$6" -rss_limit_mb="$7" -print_final_stats=1 -artifact_prefix="$dir/")
  if [[ -n "$dict" ]]; then args+=(-dict="$dict"); fi
  args+=("$dir/corpus")
  if [[ -n "$seeds" ]]; then args+=("$seeds"); fi
  if nice "$exe" "${args[@]}" >"$dir/log" 2>&1; then echo ok >"$dir/status"; else echo "exit $?" >"$dir/status"; fi
}

# fuzz_all LIST OUT SECONDS TIMEOUT RSS_MB JOBS LABEL [NAME ...]: runs the fuzzers of LIST (only
# the NAMEs when given), JOBS at a time, each in OUT/<name> after removing its last status, log
# and findings; says which with LABEL; leaves their folders in the array fuzz_dirs.
fuzz_all() {
  local list="$1" out="$2" seconds="$3" timeout="$4" rss="$5" jobs="$6" label="$7"
  shift 7
  local exe seeds dict name dir w wanted running=0
  fuzz_dirs=()
  while IFS='|' read -r exe seeds dict; do
    [[ -z "$exe" ]] && continue
    name="$(basename "$exe")"
    wanted=$(($# == 0))
    for w in "$@"; do [[ "$w" == "$name" ]] && wanted=1; done
    ((wanted)) || continue
    dir="$out/$name"
    rm -f "$dir"/status "$dir"/log "$dir"/crash-* "$dir"/timeout-* "$dir"/oom-* "$dir"/leak-* "$dir"/slow-unit-*
    mkdir -p "$dir/corpus"
    fuzz_dirs+=("$dir")
    echo "$label: fuzzing $name for ${seconds}s (log: $dir/log)"
    fuzz_one "$exe" "$seeds" "$dict" "$dir" "$seconds" "$timeout" "$rss" &
    running=$((running + 1))
    if ((running >= jobs)); then
      wait -n || true
      running=$((running - 1))
    fi
  done <"$list"
  wait || true
}
