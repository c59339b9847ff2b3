#!/usr/bin/env bash
# Installs the Debian 12 packages laguerre needs (only those missing) and builds a CMake preset.
#   tools/bootstrap.sh [--preset release|debug-asan] [--target TARGET]... [--no-build]
# Safe to run again: installed packages are skipped, the build is incremental. With --target only
# those targets (and what they need) are built, e.g. `--target laguerre` for the program alone.
set -euo pipefail
cd "$(dirname "$0")/.."

preset=release
build=1
targets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --preset) preset="$2"; shift 2 ;;
    --target) targets+=(--target "$2"); shift 2 ;;
    --no-build) build=0; shift ;;
    -h|--help) sed -n '2,5p' "$0"; exit 0 ;;
    *) echo "bootstrap: unknown argument '$1' (expected --preset NAME, --target TARGET or --no-build)" >&2; exit 2 ;;
  esac
done

packages=(
  build-essential cmake ninja-build pkg-config ccache git
  libcgal-dev libgmp-dev libmpfr-dev          # exact predicates, diagrams
  libboost-dev libboost-graph-dev             # planarity (Boyer–Myrvold), graph algorithms
  libeigen3-dev                               # linear algebra
  libsuitesparse-dev                          # CHOLMOD: supernodal Cholesky for Newton packing at 10^6 (optional)
  libopenblas0-pthread                        # the libblas.so.3/liblapack.so.3 CHOLMOD's factorization calls (~2x the reference BLAS)
  libmuparser-dev                             # metric fields given as expressions (meshing)
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev  # scenario files, CLI, JSON output
  libcairo2-dev                               # pictures (SVG, PNG)
  libgtest-dev libgmock-dev libbenchmark-dev  # tests and benchmarks
  libopenmpi-dev openmpi-bin libmetis-dev     # the parallel kernel over MPI, its partitions (sim/mpi)
  libns3-dev libgsl-dev                       # laguerre::ns3 and its example (optional; ns-3's libraries need GSL)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
started=$SECONDS
if [ ${#missing[@]} -gt 0 ]; then
  echo "bootstrap: installing ${missing[*]}"
  if [ "$(id -u)" -eq 0 ]; then sudo=(); elif command -v sudo >/dev/null; then sudo=(sudo); else
    echo "bootstrap: need root (or sudo) to install: ${missing[*]}" >&2; exit 1
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${sudo[@]}" apt-get update -qq
  "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  echo "bootstrap: packages installed in $((SECONDS - started)) s"
fi

if [ "$build" -eq 1 ]; then
  started=$SECONDS
  cmake --preset "$preset" >/dev/null
  configured=$SECONDS
  cmake --build --preset "$preset" "${targets[@]}"
  echo "bootstrap: $preset configured in $((configured - started)) s, built in $((SECONDS - configured)) s"
fi
