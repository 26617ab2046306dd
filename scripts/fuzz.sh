#!/usr/bin/env bash
# scripts/fuzz.sh [SECONDS] [TARGET...]
# Builds the libFuzzer targets of tests/fuzz (clang, ASan + UBSan, every library
# instrumented; installing the Debian packages that are missing) into build-fuzz/ and
# runs each target for SECONDS (default 30), or only the TARGETs named (point_file svg
# json sketch fit). A crash, leak, UB, timeout (an input over 10 s) or memory blow-up
# (over 2 GB) fails the run: the reproducer is written to build-fuzz/findings/<target>/
# and its path printed; replay it with build-fuzz/tests/fuzz/<target>_fuzz FILE.
# FUZZ_SEED=N fixes libFuzzer's seed (CI uses 1); unset, each run draws its own.
# The corpus grows in build-fuzz/corpus/<target>/ from the committed seeds
# (tests/fuzz/corpus/<target>/) and files of shared/data and samples/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-30}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(point_file svg json sketch fit)

source scripts/packages.sh
installMissing "${LAFAIR_LIBRARY_PACKAGES[@]}" clang-14 libclang-rt-14-dev

start=$(date +%s)
# -O2 without NDEBUG: fast enough for many runs a second, Eigen's index checks kept.
cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g" -DLAFAIR_FUZZ=ON \
  -DLAFAIR_BUILD_GUI=OFF -DLAFAIR_BUILD_TESTS=OFF -DLAFAIR_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz -j2 --target "${targets[@]/%/_fuzz}"
echo "fuzz build: $(($(date +%s) - start)) s"

# Seeds of each target beyond the committed ones: files of the formats it reads, at
# most 16 KB (a run of a larger one is slow and covers nothing more). The fit target
# takes a spread of them only: each seed is fitted once before fuzzing starts.
data=../shared/data
seedFiles() {
  local target=$1
  case "$target" in
    point_file) find "$data" samples -type f \( -name '*.csv' -o -name '*.txt' -o -name '*.dat' \) -size -16k ;;
    svg) find "$data" samples -type f -name '*.svg' -size -16k ;;
    json | sketch) find "$data" samples -type f -name '*.json' -size -16k ;;
    fit) find "$data" samples -type f \( -name '*.csv' -o -name '*.dat' -o -name '*.svg' \) -size -16k | sort | awk 'NR % 12 == 1' ;;
  esac 2>/dev/null || true
}

export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
failed=()
for target in "${targets[@]}"; do
  corpus=build-fuzz/corpus/$target findings=build-fuzz/findings/$target log=build-fuzz/logs/$target.log
  mkdir -p "$corpus" "$findings" build-fuzz/logs
  cp -n tests/fuzz/corpus/"$target"/* "$corpus"/
  # Seeds are named by their contents: files of the same name in two folders both go in.
  while IFS= read -r f; do cp -n "$f" "$corpus/$(sha1sum "$f" | cut -c1-16)-$(basename "$f")"; done < <(seedFiles "$target")
  dict=()
  [ -f tests/fuzz/"$target".dict ] && dict=(-dict=tests/fuzz/"$target".dict)
  echo "== $target: ${seconds} s, corpus $(ls "$corpus" | wc -l) files"
  # (timeout: libFuzzer stops itself after SECONDS; were a run to hang past that and
  # the loading of its corpus, it fails here with its log instead of holding CI)
  if timeout --kill-after=30 $((seconds + 300)) build-fuzz/tests/fuzz/"$target"_fuzz "$corpus" "${dict[@]}" -max_total_time="$seconds" -timeout=10 \
       -seed="${FUZZ_SEED:-0}" -rss_limit_mb=2048 -artifact_prefix="$findings/" -print_final_stats=1 >"$log" 2>&1; then
    grep -E '^stat::number_of_executed_units|^#[0-9]+.*DONE' "$log" | tail -2 || true
  else
    failed+=("$target")
    echo "!! $target FAILED (log: $log)"
    grep -E 'ERROR: |runtime error: |SUMMARY: |terminate called|what\(\)' "$log" | head -20 || true
    grep -h 'Test unit written to' "$log" | sed 's/.*written to /reproducer: /' | sort -u || true
  fi
done
echo "fuzz.sh total: $(($(date +%s) - start)) s"
[ ${#failed[@]} -eq 0 ] || echo "fuzzing found problems in: ${failed[*]}"
echo "fuzz: $((${#targets[@]} - ${#failed[@]})) passed, ${#failed[@]} failed"
[ ${#failed[@]} -eq 0 ]
