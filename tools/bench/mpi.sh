#!/usr/bin/env bash
# The MPI parallel kernel measured (issue 13 §3): PHOLD on a torus at 10^5 and 10^6 nodes, the
# sequential Simulator, then the parallel kernel on 1 and 2 ranks (this machine has 2 cores), with
# events/s, windows, copies exchanged per window, time in events vs in synchronisation, peak memory
# per rank, the exchange latency τ and the coupling factor λ = L·E/(τ·P). The trace hashes of the
# 10^5 runs are printed side by side: they must be equal (the parallel run is the sequential one).
#   tools/bench/mpi.sh [--preset release] [--sizes "316 1000"] [--until "50 5"] [--ranks "1 2"]
# --sizes are torus sides (316² = 99 856, 1000² = 10^6 nodes); --until the simulated seconds of each.
set -euo pipefail
cd "$(dirname "$0")/../.."
preset=release sides="316 1000" untils="50 5" ranks="1 2"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --preset) preset="$2"; shift 2 ;;
    --sizes) sides="$2"; shift 2 ;;
    --until) untils="$2"; shift 2 ;;
    --ranks) ranks="$2"; shift 2 ;;
    *) echo "mpi.sh: unknown argument '$1' (expected --preset, --sizes, --until or --ranks)" >&2; exit 2 ;;
  esac
done
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" --target phold_mpi >/dev/null
exe="build/$preset/tools/bench/phold_mpi"
# CI and this machine run as root, which OpenMPI refuses unless told.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "# $(date -u +%FT%TZ) $(git rev-parse --short HEAD) load: $(uptime | sed 's/.*load average: //') cores: $(nproc)"
read -r -a side_list <<<"$sides"
read -r -a until_list <<<"$untils"
for i in "${!side_list[@]}"; do
  side=${side_list[$i]} until=${until_list[$i]:-${until_list[-1]}}
  trace=$([[ $side -le 400 ]] && echo 1 || echo 0)  # the merged trace costs records on every rank
  "$exe" --side "$side" --until "$until" --sequential 1 --trace "$trace"
  for np in $ranks; do
    mpirun -np "$np" --oversubscribe --bind-to none "$exe" --side "$side" --until "$until" --trace "$trace"
  done
done
