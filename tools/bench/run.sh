#!/usr/bin/env bash
# Builds the Release preset and prints the packing benchmark table.
#   tools/bench/run.sh [--quick|--huge]   (--quick: sizes up to 10^4, about a minute;
#                                          --huge: first the 10^6 goal — Delaunay seed 1 packed to LPD by
#                                          Newton with CHOLMOD at 10^4, 10^5, 10^6, with phases, wall,
#                                          CPU and peak RSS (newton.sh, ~3 minutes idle) —, the uniform
#                                          random triangulations of 10^3 … 10^6 in binary128 with refined
#                                          radii, 1000 sampled pairs routed (~5 minutes idle), then
#                                          tools/bench/newton.sh --huge (Newton's linear solvers side by
#                                          side at 10^4, 10^5, 10^6), then 10^6 vertices to LPD with
#                                          Newton and with Anderson (hours))
# The default run takes about 5 minutes (the 10^4 plain and 10^5 whole runs dominate).
set -euo pipefail
cd "$(dirname "$0")/../.."
tools/bootstrap.sh --preset release >/dev/null
filter='^BM_(ThurstonSweep|LayoutAndLpdCheck|LayoutAndLpdCheckAtLpd|Pack)/'
case "${1:-}" in
  --quick) filter='^BM_[A-Za-z]+/(1000|10000)(/|$)' ;;
  --huge) filter='^BM_PackHuge'
          tools/bench/newton.sh --solvers cholesky --families delaunay --seed 1 10000 100000 1000000
          tools/bench/newton.sh --solvers cholesky --families uniform-triangulation --arithmetics binary128 \
            --termination radius-only --pairs 1000 --seed 1 1000 10000 100000 1000000
          tools/bench/newton.sh --huge ;;
esac
build/release/tools/bench/bench_packing --benchmark_filter="$filter" --benchmark_counters_tabular=true
