#!/bin/sh
# Table 2, Figures 13 and 14 (the optimizer, §3.3) on the bundled kitten scan.
# Usage: bench/optimizer_bench.sh [BUILD_DIR]   (default: build)
# Writes bench/results/optimizer_table2.txt and bench/results/optimizer_figure14.txt.
set -e
cd "$(dirname "$0")/.."
build="${1:-build}"
cmake --build "$build" --target optimizer_bench -j2
"$build/optimizer_bench" all --points data/kitten_scan.ply --output bench/results
