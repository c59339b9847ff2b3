#!/usr/bin/env bash
# The packing protocol live over UDP on 127.0.0.1 (`laguerre live`, 1, 2 and 4 worker processes)
# against the simulator (`laguerre simulate`) on the same random Delaunay triangulations: wall time of
# the packing phase, datagrams/s (over the whole run), messages and bytes per node, peak memory of the
# largest process, and the bit-for-bit check against core::pack of every row.
#   tools/bench/live.sh [--processes "1 2 4"] [--partitions "blocks metis"] [--loss P] [--timeout SECONDS] [SIZES…]
# Each P > 1 runs once per --partitions entry (`laguerre live --partition`: blocks of indices, or
# METIS, which cuts fewer links). wire_B/node: UDP bytes (headers included) per node; 0 with one process. --loss runs both sides
# with that loss (reliability layer on; the simulator's links keep their 1 ms latency).
# Defaults: sizes 100 1000; N = n/1000 Thurston steps per round (at least 1), 1000 sampled pairs.
# Each run is bounded by --timeout (default 600 s; `laguerre live --timeout`, simulate by `timeout`).
# LAGUERRE_EXE=path uses that program instead of building the release preset with tools/bootstrap.sh.
set -euo pipefail
cd "$(dirname "$0")/../.."

processes="1 2 4" partitions="blocks metis" timeout=600 loss=0 sizes=()
while [ $# -gt 0 ]; do
  case "$1" in
    --processes) processes=$2; shift 2 ;;
    --partitions) partitions=$2; shift 2 ;;
    --timeout) timeout=$2; shift 2 ;;
    --loss) loss=$2; shift 2 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) sizes+=("$1"); shift ;;
  esac
done
[ ${#sizes[@]} -eq 0 ] && sizes=(100 1000)

. tools/bench/common.sh
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
printf '%7s %-14s %10s %9s %12s %10s %11s %12s %9s %8s %10s\n' nodes run iterations wall_s datagrams/s msgs/node \
  bytes/node wire_B/node peak_MiB vs_sim verify
for n in "${sizes[@]}"; do
  steps=$(( n / 1000 )); [ "$steps" -lt 1 ] && steps=1
  "$laguerre" generate delaunay -n "$n" --seed 42 -o "$dir/g$n.txt" 2>/dev/null
  common=(-N "$steps" --pairs 1000 --loss "$loss" --verify --json)
  timeout "$timeout" "$laguerre" simulate "$dir/g$n.txt" "${common[@]}" > "$dir/sim$n.json"
  runs=()
  for p in $processes; do
    for part in $partitions; do
      [ "$p" -eq 1 ] && [ "$part" != "$(set -- $partitions; echo "$1")" ] && continue  # one worker: no partition
      "$laguerre" live "$dir/g$n.txt" --processes "$p" --partition "$part" --timeout "$timeout" "${common[@]}" \
        > "$dir/live$n-$p-$part.json"
      runs+=("$p-$part")
    done
  done
  python3 - "$n" "$dir" "${runs[@]}" <<'PY'
import json, sys
n, d, runs = int(sys.argv[1]), sys.argv[2], sys.argv[3:]
sim = json.load(open(f"{d}/sim{n}.json"))
def verdict(doc):
    return "bit-exact" if "identical" in doc["verify"] else doc["verify"]
print(f"{n:>7} {'simulate':<14} {sim['iterations']:>10} {sim['wall_seconds']:>9.3f} {'-':>12} "
      f"{sim['messages_per_node_mean']:>10.1f} {sim['bytes_per_node_mean']:>11.0f} {'-':>12} "
      f"{sim['peak_memory_bytes'] / 2**20:>9.1f} {1.0:>8.2f} {verdict(sim):>10}")
for run in runs:
    p, part = run.split("-")
    doc = json.load(open(f"{d}/live{n}-{run}.json"))
    live = doc["live"]
    wall = live["phase_wall_seconds"][0]
    peak = max(w["peak_memory_bytes"] for w in live["workers"])
    print(f"{n:>7} {'live P=' + p + ('' if p == '1' else '/' + part):<14} {doc['iterations']:>10} {wall:>9.3f} {live['datagrams_per_second']:>12.3g} "
          f"{doc['messages_per_node_mean']:>10.1f} {doc['bytes_per_node_mean']:>11.0f} "
          f"{live['datagram_bytes'] / n:>12.0f} {peak / 2**20:>9.1f} "
          f"{wall / sim['wall_seconds']:>8.2f} {verdict(doc):>10}")
PY
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "wall_s: packing phase (live) or the simulation (simulate); vs_sim = wall_s / simulate's wall_s;"
echo "datagrams/s: UDP datagrams over the whole live run (0 with one process: every message stays in memory);"
echo "peak_MiB: the largest worker process (live), the process (simulate)"
