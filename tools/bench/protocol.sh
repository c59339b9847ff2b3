#!/usr/bin/env bash
# The distributed packing protocol in the simulator on random Delaunay triangulations: wall time,
# events/s, messages and bytes per node, peak memory, iterations to LPD.
#   tools/bench/protocol.sh [SIZES…]      (default: 1000 10000; N = n/1000 sweeps per round, at least 1)
set -euo pipefail
cd "$(dirname "$0")/../.."
tools/bootstrap.sh --preset release >/dev/null
laguerre=build/release/tools/laguerre
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(1000 10000)
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf '%8s %4s %10s %8s %12s %12s %12s %12s %10s %12s\n' nodes N iterations rounds wall_s events/s \
  msgs/node bytes/node peak_MiB verify
for n in "${sizes[@]}"; do
  steps=$(( n / 1000 )); [ "$steps" -lt 1 ] && steps=1
  "$laguerre" generate delaunay -n "$n" --seed 42 -o "$dir/g$n.txt" 2>/dev/null
  "$laguerre" simulate "$dir/g$n.txt" -N "$steps" --pairs 1000 --verify --json > "$dir/r$n.json"
  python3 - "$dir/r$n.json" "$n" "$steps" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
print(f"{sys.argv[2]:>8} {sys.argv[3]:>4} {d['iterations']:>10} {d['rounds']:>8} {d['wall_seconds']:>12.2f} "
      f"{d['events_per_second']:>12.3g} {d['messages_per_node_mean']:>12.1f} {d['bytes_per_node_mean']:>12.0f} "
      f"{d['peak_memory_bytes'] / 2**20:>10.1f} {'bit-exact' if 'identical' in d.get('verify', '') else d.get('verify', '?'):>12}")
PY
done
