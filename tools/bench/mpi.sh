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
out=$(mktemp)
trap 'rm -f "$out"' EXIT
for i in "${!side_list[@]}"; do
  side=${side_list[$i]} until=${until_list[$i]:-${until_list[-1]}}
  trace=$([[ $side -le 400 ]] && echo 1 || echo 0)  # the merged trace costs records on every rank
  "$exe" --side "$side" --until "$until" --sequential 1 --trace "$trace" | tee -a "$out"
  for np in $ranks; do
    mpirun -np "$np" --oversubscribe --bind-to none "$exe" --side "$side" --until "$until" --trace "$trace" | tee -a "$out"
  done
done

# The scaling model (README, "Scaling out"), fitted to this run: c_e = CPU ns per event of the
# smallest sequential run; k from the METIS cut of the 2-rank runs (cut fraction = k·sqrt(P/n));
# a remote copy costs c_m = c_e more (encode, exchange, decode); τ(P) = TAU0·log2 P + TAU1·P
# (small-message MPI_Alltoall on a cluster network: an assumption, not measured here; set TAU0_US,
# TAU1_US from the cluster's osu_alltoall). PHOLD with one message per node, mean delay 1.1 s,
# lookahead 0.1 s: m = n/11 events per window in all, m/P per rank, the slowest of P ranks doing
# m/P + sqrt(2 (m/P) ln P) (Poisson imbalance).
awk -v tau0="${TAU0_US:-3}" -v tau1="${TAU1_US:-0.3}" '
  function field(line, key,   i, n, kv) { n = split(line, kv, " "); for (i = 1; i <= n; ++i) if (index(kv[i], key "=") == 1) return substr(kv[i], length(key) + 2); return "" }
  /mode=sequential/ && ce == "" { ce = field($0, "ns_per_event_cpu") * 1e-9 }
  /mode=parallel ranks=2/ { nodes = field($0, "nodes"); cut = field($0, "cut_links"); ks += (cut / (4 * nodes)) / sqrt(2 / nodes); kn++ }
  END {
    if (ce == "" || kn == 0) { print "# model: needs a sequential run and a 2-rank run"; exit }
    k = ks / kn
    printf "# model: c_e = %.0f ns/event (CPU, sequential), k = %.2f (cut fraction = k*sqrt(P/n)), tau(P) = %g us*log2(P) + %g us*P\n", ce * 1e9, k, tau0, tau1
    printf "# predicted PHOLD speed-up S(P) and coupling lambda = (n/11)*c_e/tau(P)\n"
    printf "# %-6s", "ranks"; split("1e6 1e7 1e8", ns, " "); for (j = 1; j <= 3; ++j) printf " | n=%-4s S     lambda", ns[j]; printf "\n"
    split("2 8 16 64 256 1024", ps, " ")
    for (i = 1; i <= 6; ++i) {
      P = ps[i]; tau = (tau0 * log(P) / log(2) + tau1 * P) * 1e-6
      printf "  %-6d", P
      for (j = 1; j <= 3; ++j) {
        n = ns[j] + 0; m = n / 11; mp = m / P
        t1 = ce * m
        tp = ce * (mp + sqrt(2 * mp * log(P))) + tau + ce * mp * k * sqrt(P / n)
        printf " | %10.1f %8.1f", t1 / tp, m * ce / tau
      }
      printf "\n"
    }
  }' "$out"
