#!/usr/bin/env bash
# PHOLD side by side: the laguerre::sim kernel against ns-3 3.37 (Debian's libns3-dev), same
# workload and the same random numbers on both sides (see tools/bench/phold_common.hpp).
#   tools/bench/phold.sh [--events N] [--repeat R] [--lps 10000,100000,1000000]
#                        [--schedulers "Map Heap Calendar PriorityQueue"] [--timeout SECONDS]
#                        [--clock cpu|wall] [--no-build]
# Installs the ns-3 packages if missing (root or sudo), builds phold_laguerre and phold_ns3 in
# build/phold (--no-build: use the programs already there), runs every (size, engine) R times (best kept: other processes only slow a run
# down), and prints one table. A run that exceeds the timeout (ns-3's CalendarScheduler at 10^6
# LPs takes many minutes) is reported as "t/o" (with --clock wall: as the upper bound "<x"). Defaults: 10^7 events, best of 3,
# events per second of the process's CPU time (--clock cpu; on a shared machine wall time also
# counts the time other processes hold the cores; --clock wall uses elapsed time instead).
# Population: each LP starts with one event and every event schedules exactly one, so exactly
# LPs events are pending at all times, on both sides.
# Columns: "laguerre" uses Kernel::set_prefetch (the kernel prefetches the state of the LP four
# events ahead); "no hint" is the same run without it; ns-3 has no equivalent. The ratio is
# laguerre / best ns-3 scheduler (in parentheses: without the hint).
set -euo pipefail
cd "$(dirname "$0")/../.."

events=10000000 repeat=3 lps=10000,100000,1000000 schedulers="Map Heap Calendar PriorityQueue" limit=120 clock=cpu build_programs=1
while [ $# -gt 0 ]; do
  case "$1" in
    --events) events=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --lps) lps=$2; shift 2 ;;
    --schedulers) schedulers=$2; shift 2 ;;
    --timeout) limit=$2; shift 2 ;;
    --clock) clock=$2; shift 2 ;;
    --no-build) build_programs=0; shift ;;
    *) echo "phold.sh: unknown option $1" >&2; exit 2 ;;
  esac
done

if ! dpkg -s libns3-dev ns3 libgsl-dev >/dev/null 2>&1; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo=sudo
  $sudo apt-get install -y libns3-dev ns3 libgsl-dev >&2
fi

build=build/phold
if [ "$build_programs" -eq 1 ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DLAGUERRE_WERROR=ON -DLAGUERRE_BENCH_NS3=ON >/dev/null
  cmake --build "$build" --target phold_laguerre phold_ns3 -j2 >&2
fi
bench="$build/tools/bench"

# Output fields of both programs: 5 = events per wall second, 8 = events per CPU second.
field=8; [ "$clock" = wall ] && field=5
case "$clock" in cpu|wall) ;; *) echo "phold.sh: --clock expects cpu or wall, found $clock" >&2; exit 2 ;; esac

# best <command…>: the largest events/s (field $field) over $repeat runs, or "t/o" ("<bound" with
# --clock wall) on timeout.
best() {
  local top=0 line rate
  for _ in $(seq "$repeat"); do
    if line=$(timeout "$limit" "$@"); then
      rate=$(echo "$line" | awk -v f="$field" '{print $f}')
      top=$(awk -v a="$top" -v b="$rate" 'BEGIN {print (b > a) ? b : a}')
    else
      # A wall-clock timeout bounds the wall rate only (CPU time may be far below the timeout).
      if [ "$clock" = wall ]; then awk -v e="$events" -v t="$limit" 'BEGIN {printf "<%.0f\n", e / t}'; else echo "t/o"; fi
      return
    fi
  done
  echo "$top"
}

m() { awk -v x="$1" 'BEGIN { if (x == "t/o") printf "%10s", x; else if (x ~ /^</) printf "%9s", "<" sprintf("%.2fM", substr(x, 2) / 1e6); else printf "%9.2fM", x / 1e6 }'; }

printf "PHOLD, %s events per run, best of %s; events per %s second (M = 10^6)\n" "$events" "$repeat" "$clock"
printf "%-9s %10s %10s" "LPs" "laguerre" "no hint"  # ns-3 columns: its schedulers
for s in $schedulers; do printf " %10s" "${s/PriorityQueue/PrioQueue}"; done
printf " %10s %7s %9s\n" "best ns-3" "ratio" "(no hint)"
for n in ${lps//,/ }; do
  ours=$(best "$bench/phold_laguerre" --lps "$n" --events "$events")
  plain=$(best "$bench/phold_laguerre" --lps "$n" --events "$events" --prefetch 0)
  printf "%-9s %10s %10s" "$n" "$(m "$ours")" "$(m "$plain")"
  top=0
  for s in $schedulers; do
    r=$(best "$bench/phold_ns3" --scheduler "ns3::${s}Scheduler" --lps "$n" --events "$events")
    printf " %10s" "$(m "$r")"
    case "$r" in "<"* | "t/o") ;; *) top=$(awk -v a="$top" -v b="$r" 'BEGIN {print (b > a) ? b : a}') ;; esac
  done
  printf " %10s %6.2fx %8s\n" "$(m "$top")" "$(awk -v a="$ours" -v b="$top" 'BEGIN {print a / b}')" \
    "($(awk -v a="$plain" -v b="$top" 'BEGIN {printf "%.2fx", a / b}'))"
done
