#!/usr/bin/env bash
# Installs the Debian packages pdd needs, skipping those already installed.
# Idempotent; needs root (or sudo) for apt-get.
#   scripts/setup.sh          what the build, the tests and the example need
#   scripts/setup.sh --bench  also what bench/solvers.sh and bench/scale.sh use
#   scripts/setup.sh --fuzz   also clang and libFuzzer, for scripts/fuzz.sh
set -euo pipefail

packages=(
  cmake g++ make
  libcgal-dev libeigen3-dev
  libsuitesparse-dev libopenblas-dev libtbb-dev
  libcli11-dev libgtest-dev libbenchmark-dev
  time jq  # bench/shared_data.sh: /usr/bin/time -v, JSON fields
  libcgal-demo  # bench/table1.sh: CGAL's data set (data/points_3/hippo1.ply)
  python3-dev pybind11-dev python3-numpy python3-pytest  # the Python module and its tests
  python3-open3d  # the Python module's Open3D conversions, tested when importable
)
if [ "${1:-}" = "--bench" ]; then
  packages+=(
    libhypre-dev mpi-default-dev  # bench/solvers.sh: BoomerAMG beside pdd's multigrid
  )
fi
if [ "${1:-}" = "--fuzz" ]; then
  packages+=(clang libclang-rt-dev)  # scripts/fuzz.sh: libFuzzer and the sanitizers' runtime
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages already installed"
  exit 0
fi

sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
