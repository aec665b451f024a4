#!/usr/bin/env bash
# Builds pdd with AddressSanitizer and UndefinedBehaviorSanitizer (g++'s) under
# build-sanitize/ and runs the C++ test suite there: any memory error, leak or
# undefined behaviour fails the test that hit it. The Python tests are left
# out: Debian's python3 is not built with the sanitizers' runtime.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
flags="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPDD_BUILD_PYTHON=OFF \
  -DPDD_BUILD_BENCH=OFF -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  > build-sanitize.log 2>&1 || { cat build-sanitize.log; exit 1; }
cmake --build build-sanitize -j "$(nproc)" >> build-sanitize.log 2>&1 || { tail -n 60 build-sanitize.log; exit 1; }
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The sanitizers make the runs 2-5x slower: ctest's timeout is raised to match.
ctest --test-dir build-sanitize --output-on-failure -j "$(nproc)" --timeout 1500 "$@"
