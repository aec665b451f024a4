#!/usr/bin/env bash
# The linear solvers at scale (issue 15): SSD's system on progressive domains of
# about 50k, 200k and 1M vertices by multigrid CG (pdd), CG + incomplete
# Cholesky, CG + BoomerAMG (hypre) and CHOLMOD; see bench/solvers_bench.cpp.
#
#   bench/solvers.sh [--sizes 50000,200000,1000000]
#
# Installs hypre (scripts/setup.sh --bench), configures build/ so that
# solvers_bench links it, and writes bench/results/solvers.txt.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash scripts/setup.sh --bench
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build --target solvers_bench -j "$(nproc)" > /dev/null
./build/solvers_bench --out bench/results/solvers.txt "$@"
