#!/usr/bin/env bash
# Real scans: open surfaces (--trim), outliers (--outliers) and colours, beside PoissonRecon +
# SurfaceTrimmer and Open3D (issue 16): see bench/real_scans.py, which this runs.
set -euo pipefail
exec /usr/bin/python3 "$(dirname "$0")/real_scans.py" "$@"
