#!/usr/bin/env bash
# Point sets without normals or with half of them flipped, against the true normals and
# Open3D's pipeline (issue 17): see bench/unoriented.py, which this runs.
set -euo pipefail
exec /usr/bin/python3 "$(dirname "$0")/unoriented.py" "$@"
