#!/usr/bin/env bash
# The distributed packing protocol in the simulator on random Delaunay triangulations: wall time,
# events/s, messages and bytes per node, peak memory (total and per node), iterations to LPD.
#   tools/bench/protocol.sh [--cap ITERATIONS] [--cap-from NODES] [--termination MODE] [--steps N] [SIZES…]
# Defaults: sizes 1000 10000 100000; N = n/1000 Thurston steps per round (at least 1); --steps fixes N.
# --termination layout (default), radius-only or both: `laguerre simulate --termination`, one row per
# mode and size (docs/radius-only.md); the waves column counts the layout waves the run made, sim_s is
# the simulated time at which the last node finished (the protocol's time to termination).
# Convergence to LPD at 10^5 nodes takes tens of thousands of sweeps, so sizes ≥ --cap-from (default
# 100000) run a fixed budget of --cap Thurston steps (default 100: one round of N = 100 steps, with its
# layout wave and convergecast; `laguerre simulate --max-iterations`) and their row says "capped@K":
# the per-node figures are then those of K steps, not of a converged run, and the bit-for-bit check
# against core::pack is skipped. An uncapped row that does not converge says "NOT converged".
# cpu_s is the CPU time of the whole `laguerre simulate` process (set-up and forwarding included): on a
# shared machine wall_s − cpu_s is time the cores spent on other processes, and the load averages
# (uptime) are printed before and after the table.
# LAGUERRE_EXE=path uses that program instead of building the release preset with tools/bootstrap.sh.
set -euo pipefail
cd "$(dirname "$0")/../.."

cap=100 cap_from=100000 sizes=() terminations=(layout) fixed_steps=
while [ $# -gt 0 ]; do
  case "$1" in
    --cap) cap=$2; shift 2 ;;
    --cap-from) cap_from=$2; shift 2 ;;
    --steps) fixed_steps=$2; shift 2 ;;
    --termination) case "$2" in both) terminations=(layout radius-only) ;; *) terminations=("$2") ;; esac; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0"; exit 0 ;;
    *) sizes+=("$1"); shift ;;
  esac
done
[ ${#sizes[@]} -eq 0 ] && sizes=(1000 10000 100000)

. tools/bench/common.sh
echo "load before: $(uptime)"
printf '%8s %4s %12s %10s %6s %6s %13s %9s %8s %9s %10s %10s %11s %10s %13s %12s\n' nodes N termination iterations \
  rounds waves status wall_s cpu_s sim_s events/s msgs/node bytes/node peak_MiB peak_KiB/node verify
for n in "${sizes[@]}"; do
  steps=$(( n / 1000 )); [ "$steps" -lt 1 ] && steps=1
  [ -n "$fixed_steps" ] && steps=$fixed_steps
  "$laguerre" generate delaunay -n "$n" --seed 42 -o "$dir/g$n.txt" 2>/dev/null
for term in "${terminations[@]}"; do
  if [ "$n" -ge "$cap_from" ]; then
    args=(--max-iterations "$cap" --pairs 10) label="capped@$cap"
  else
    args=(--pairs 1000 --verify) label=""
  fi
  rc=0
  start_cpu=$(awk '{print $14 + $15 + $16 + $17}' /proc/$$/stat)
  "$laguerre" simulate "$dir/g$n.txt" -N "$steps" --termination "$term" "${args[@]}" --json > "$dir/r$n.json" || rc=$?
  # Children's user + system time (cutime + cstime, fields 16 and 17 of /proc/PID/stat, in clock ticks).
  cpu=$(awk -v t0="$start_cpu" -v hz="$(getconf CLK_TCK)" '{printf "%.2f", ($14 + $15 + $16 + $17 - t0) / hz}' /proc/$$/stat)
  # Exit status 3: not converged (expected when capped); anything else is a real failure.
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 3 ]; then
    echo "protocol.sh: laguerre simulate failed on $n nodes (exit status $rc)" >&2
    exit "$rc"
  fi
  [ -z "$label" ] && label=$([ "$rc" -eq 0 ] && echo converged || echo "NOT converged")
  python3 - "$dir/r$n.json" "$n" "$steps" "$label" "$cpu" "$term" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
n, steps, label, cpu, term = int(sys.argv[2]), sys.argv[3], sys.argv[4], float(sys.argv[5]), sys.argv[6]
# A triangulation's layout wave sends one PlacedMsg per dart.
waves = d["by_phase"].get("placed", {}).get("messages", 0) // (2 * d["edges"])
v = d.get("verify")
verify = "n/a (capped)" if v is None else ("bit-exact" if "identical" in v else v)
print(f"{n:>8} {steps:>4} {term:>12} {d['iterations']:>10} {d['rounds']:>6} {waves:>6} {label:>13} {d['wall_seconds']:>9.2f} {cpu:>8.2f} {d['finished_seconds']:>9.2f} "
      f"{d['events_per_second']:>10.3g} {d['messages_per_node_mean']:>10.1f} {d['bytes_per_node_mean']:>11.0f} "
      f"{d['peak_memory_bytes'] / 2**20:>10.1f} {d['peak_memory_bytes'] / 1024 / n:>13.2f} {verify:>12}")
PY
done
done
echo "load after: $(uptime)"
