#!/usr/bin/env bash
# Builds the readers' fuzz targets (fuzz/, clang's libFuzzer with AddressSanitizer
# and UndefinedBehaviorSanitizer) under build-fuzz/ and fuzzes each reader for
# SECONDS (default 30) from its seed corpus in fuzz/corpus/<format>/, with a
# fixed seed. Fails on any crash, sanitizer report, other exception than
# InputError, write-read mismatch, input slower than 10 s or memory over 2 GB;
# the input at fault is left in build-fuzz/crashes/, to be added to the corpus
# with its fix.
#   scripts/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-30}"
bash scripts/setup.sh --fuzz
cmake -S fuzz -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  > build-fuzz.log 2>&1 || { cat build-fuzz.log; exit 1; }
cmake --build build-fuzz -j "$(nproc)" >> build-fuzz.log 2>&1 || { tail -n 60 build-fuzz.log; exit 1; }
mkdir -p build-fuzz/crashes
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
for format in ply off obj xyz; do
  # New inputs go to a scratch corpus; the seeds in the repository stay as they are.
  work="build-fuzz/corpus/$format"
  mkdir -p "$work"
  if ! build-fuzz/${format}_fuzzer -seed=1 -max_total_time="$seconds" -timeout=10 \
      -rss_limit_mb=2048 -malloc_limit_mb=2048 -max_len=4096 -print_final_stats=1 \
      -artifact_prefix="build-fuzz/crashes/${format}-" "$work" "fuzz/corpus/$format" \
      > "build-fuzz/$format.log" 2>&1; then
    tail -n 40 "build-fuzz/$format.log"
    echo "fuzz: the $format reader failed; the input is in build-fuzz/crashes/"
    exit 1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "build-fuzz/$format.log" | grep -o '[0-9]*$')
  echo "fuzz: $format reader, $runs inputs in ${seconds} s, no failure"
done
