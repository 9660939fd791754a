#!/usr/bin/env bash
# Runs every fuzz harness of a GLINT_FUZZ build one after another (make fuzz), then prints
# executions and crashes per harness. Usage: run-fuzzers.sh BUILD_DIR [HARNESS...]
# FUZZ_SECONDS sets the time per harness (default 60; issue 19's table used 600).
set -uo pipefail

build=${1:?usage: run-fuzzers.sh BUILD_DIR [HARNESS...]}
shift
seconds=${FUZZ_SECONDS:-60}
source_dir=$(cd "$(dirname "$0")/.." && pwd)
harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then
  harnesses=(ply exr png jpeg tiff transforms edit_file train_config request gltf colmap_text colmap_binary nerfstudio)
fi

# Longest input per format: a few times the largest seed, so mutations can grow a file
# without the fuzzer spending its time on megabyte inputs.
max_len() {
  case "$1" in
    ply | exr | tiff | gltf | transforms) echo 8192 ;;
    *) echo 4096 ;;
  esac
}

results=()
for h in "${harnesses[@]}"; do
  program="$build/fuzz/fuzz_$h"
  if [ ! -x "$program" ]; then
    echo "run-fuzzers: $program is missing (build the glint_fuzzers target)" >&2
    exit 1
  fi
  # New inputs go to build-fuzz/corpus/<h>; the committed seeds are read, never written.
  work="$build/corpus/$h"
  crashes="$build/crashes/$h"
  log="$build/logs/$h.log"
  mkdir -p "$work" "$crashes" "$(dirname "$log")"
  echo "run-fuzzers: fuzz_$h for ${seconds}s (log: $log)"
  # -rss_limit_mb: a 3 GB allocation from a 600-byte file is a finding, not a slow run.
  # -close_fd_mask=3: the parsers' warnings would drown libFuzzer's own report.
  "$program" "$work" "$source_dir/fuzz/corpus/$h" -max_total_time="$seconds" -max_len="$(max_len "$h")" \
    -rss_limit_mb=2048 -timeout=20 -close_fd_mask=3 -print_final_stats=1 \
    -artifact_prefix="$crashes/" >"$log" 2>&1
  status=$?
  execs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$')
  found=$(find "$crashes" -type f \( -name 'crash-*' -o -name 'oom-*' -o -name 'timeout-*' -o -name 'leak-*' \) | wc -l)
  results+=("$h ${execs:-?} $found $status")
done

printf '\n%-14s %14s %8s  %s\n' harness executions crashes "exit status (0: ran out its time)"
for r in "${results[@]}"; do
  read -r h execs found status <<<"$r"
  printf '%-14s %14s %8s  %s\n' "$h" "$execs" "$found" "$status"
done
