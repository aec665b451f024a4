#!/usr/bin/env bash
# Installs what is missing, builds, and reconstructs the bundled kitten scan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
build/pdd reconstruct data/kitten_scan.ply -o out/kitten.ply --stats out/kitten_stats.json
echo "The mesh is in $(pwd)/out/kitten.ply (statistics: out/kitten_stats.json)"
