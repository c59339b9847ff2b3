#!/usr/bin/env bash
# PHOLD side by side: the laguerre::sim kernel against ns-3 3.37 (Debian's libns3-dev), same
# workload and the same random numbers on both sides (see tools/bench/phold_common.hpp).
#   tools/bench/phold.sh [--events N] [--repeat R] [--lps 10000,100000,1000000]
#                        [--schedulers "Map Heap Calendar PriorityQueue"] [--timeout SECONDS]
# Installs the ns-3 packages if missing (root or sudo), builds phold_laguerre and phold_ns3 in
# build/phold, runs every (size, engine) R times (best kept: other processes only slow a run
# down), and prints one table. A run that exceeds the timeout (ns-3's CalendarScheduler at 10^6
# LPs takes many minutes) is reported as an upper bound "<x". Defaults: 10^7 events, best of 3.
set -euo pipefail
cd "$(dirname "$0")/../.."

events=10000000 repeat=3 lps=10000,100000,1000000 schedulers="Map Heap Calendar PriorityQueue" limit=120
while [ $# -gt 0 ]; do
  case "$1" in
    --events) events=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --lps) lps=$2; shift 2 ;;
    --schedulers) schedulers=$2; shift 2 ;;
    --timeout) limit=$2; shift 2 ;;
    *) echo "phold.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

if ! dpkg -s libns3-dev ns3 libgsl-dev >/dev/null 2>&1; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo=sudo
  $sudo apt-get install -y libns3-dev ns3 libgsl-dev >&2
fi

build=build/phold
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DLAGUERRE_WERROR=ON -DLAGUERRE_BUILD_TESTS=OFF \
      -DLAGUERRE_BENCH_NS3=ON >/dev/null
cmake --build "$build" --target phold_laguerre phold_ns3 -j2 >&2
bench="$build/tools/bench"

# best <command…>: the largest events/s (field 5) over $repeat runs, or "<bound" on timeout.
best() {
  local top=0 line rate
  for _ in $(seq "$repeat"); do
    if line=$(timeout "$limit" "$@"); then
      rate=$(echo "$line" | awk '{print $5}')
      top=$(awk -v a="$top" -v b="$rate" 'BEGIN {print (b > a) ? b : a}')
    else
      awk -v e="$events" -v t="$limit" 'BEGIN {printf "<%.0f\n", e / t}'
      return
    fi
  done
  echo "$top"
}

m() { awk -v x="$1" 'BEGIN { if (x ~ /^</) printf "%9s", "<" sprintf("%.2fM", substr(x, 2) / 1e6); else printf "%9.2fM", x / 1e6 }'; }

printf "PHOLD, %s events per run, best of %s; events/s (M = 10^6)\n" "$events" "$repeat"
printf "%-9s %10s" "LPs" "laguerre"  # ns-3 columns: its schedulers
for s in $schedulers; do printf " %10s" "${s/PriorityQueue/PrioQueue}"; done
printf " %10s %7s\n" "best ns-3" "ratio"
for n in ${lps//,/ }; do
  ours=$(best "$bench/phold_laguerre" --lps "$n" --events "$events")
  printf "%-9s %10s" "$n" "$(m "$ours")"
  top=0
  for s in $schedulers; do
    r=$(best "$bench/phold_ns3" --scheduler "ns3::${s}Scheduler" --lps "$n" --events "$events")
    printf " %10s" "$(m "$r")"
    case "$r" in "<"*) ;; *) top=$(awk -v a="$top" -v b="$r" 'BEGIN {print (b > a) ? b : a}') ;; esac
  done
  printf " %10s %6.2fx\n" "$(m "$top")" "$(awk -v a="$ours" -v b="$top" 'BEGIN {print a / b}')"
done
