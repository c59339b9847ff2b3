#!/usr/bin/env bash
# Builds the Release preset and prints the packing benchmark table.
#   tools/bench/run.sh [--quick]      (--quick: sizes up to 10^4 only, about a minute)
# The full run takes about 15 minutes (the 10^5 whole runs dominate).
set -euo pipefail
cd "$(dirname "$0")/../.."
tools/bootstrap.sh --preset release >/dev/null
filter='.*'
[ "${1:-}" = "--quick" ] && filter='.*/(1000|10000)(/|$).*'
build/release/tools/bench/bench_packing --benchmark_filter="$filter" --benchmark_counters_tabular=true
