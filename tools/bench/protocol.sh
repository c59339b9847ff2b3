#!/usr/bin/env bash
# The distributed packing protocol at scale, every message simulated and no iteration cap: per graph
# family, size and mode one `laguerre simulate` run to LPD/GLPD, printing mode, N, rounds, iterations,
# messages and bytes per node, simulated time, wall and CPU time, events/s, peak memory per node
# (the process's peak RSS at the end of the protocol, graph included, / nodes) and whether the result
# equals core::pack bit for bit; then, per family and mode, the growth law of messages per node fitted
# on the converged rows (least squares on log msgs/node = a + b·log n: msgs/node ∝ n^b).
#   tools/bench/protocol.sh [--families "…"] [--modes "…"] [-N STEPS] [--timeout SECONDS]
#                           [--verify-to NODES] [--seed S] [--termination layout|radius-only|radius-flood|both|all] [SIZES…]
# Defaults: sizes 1000 10000; families uniform-triangulation uniform-three-connected delaunay
# unit-disk-field (`laguerre generate`: unit-disk-field = LDel² of a unit-disk field, 3-connected core);
# modes chebyshev (the best local acceleration; also plain, local-superstep); N = max(1, n/1000)
# Thurston steps per round unless -N; timeout 900 s per run (a row that times out says so, with
# the figures of nothing); rows up to --verify-to nodes (default 10000) are checked against core::pack.
# cpu_s is the CPU time of the whole `laguerre simulate` process: on a shared machine wall_s − cpu_s
# is time the cores spent on other processes; the load averages (uptime) are printed before and after.
# --termination radius-only (or both: a row each) runs `simulate --termination radius-only`
# (docs/radius-only.md); its rows are labelled MODE+ro (radius-flood: MODE+rf; all: the three), and the waves column counts the layout waves
# a run made (its PlacedMsg count over the darts, exact on triangulations); setup/node counts the set-up's messages
# (depth, election, start, wave, shape, height) per node.
# LAGUERRE_EXE=path uses that program instead of building the release preset with tools/bootstrap.sh.
set -euo pipefail
cd "$(dirname "$0")/../.."

families="uniform-triangulation uniform-three-connected delaunay unit-disk-field" modes="chebyshev"
steps="" timeout_s=900 verify_to=10000 seed=42 sizes=() terminations="layout"
while [ $# -gt 0 ]; do
  case "$1" in
    --families) families=$2; shift 2 ;;
    --modes) modes=$2; shift 2 ;;
    -N) steps=$2; shift 2 ;;
    --timeout) timeout_s=$2; shift 2 ;;
    --verify-to) verify_to=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --termination) case "$2" in both) terminations="layout radius-only" ;; all) terminations="layout radius-only radius-flood" ;;
                     *) terminations=$2 ;; esac; shift 2 ;;
    -h|--help) sed -n '2,22p' "$0"; exit 0 ;;
    *) sizes+=("$1"); shift ;;
  esac
done
[ ${#sizes[@]} -eq 0 ] && sizes=(1000 10000)

. tools/bench/common.sh
echo "load before: $(uptime)"
: >"$dir/rows"
printf '%-24s %7s %-15s %4s %6s %6s %6s %10s %10s %11s %9s %9s %8s %9s %8s %-13s %s\n' family nodes mode N rounds iters \
  waves msgs/node setup/node bytes/node sim_s wall_s cpu_s events/s KiB/node status '=core'
for family in $families; do
  for n in "${sizes[@]}"; do
    g="$dir/$family-$n.txt"
    format=coords; case "$family" in uniform-*) format=edges ;; esac
    "$laguerre" generate "$family" -n "$n" --seed "$seed" --format "$format" -o "$g" 2>/dev/null
    for mode in $modes; do
     for term in $terminations; do
      label=$mode; case "$term" in radius-only) label=$mode+ro ;; radius-flood) label=$mode+rf ;; esac
      N=${steps:-$(( n / 1000 ))}; [ "$N" -lt 1 ] && N=1
      verify=(); [ "$n" -le "$verify_to" ] && verify=(--verify)
      rc=0
      start_cpu=$(awk '{print $16 + $17}' /proc/$$/stat)
      timeout "$timeout_s" "$laguerre" simulate "$g" --accelerate "$mode" --termination "$term" -N "$N" --pairs 10 --json "${verify[@]}" \
        >"$dir/out.json" 2>/dev/null || rc=$?
      # Children's user + system time (cutime + cstime, fields 16 and 17 of /proc/PID/stat, in clock ticks).
      cpu=$(awk -v t0="$start_cpu" -v hz="$(getconf CLK_TCK)" '{printf "%.1f", ($16 + $17 - t0) / hz}' /proc/$$/stat)
      if [ "$rc" -eq 124 ]; then
        printf '%-24s %7s %-15s %4s %6s   (did not finish within %s s, cpu %s s)\n' "$family" "$n" "$label" "$N" - \
          "$timeout_s" "$cpu"
        continue
      fi
      # Exit status 3: not converged; anything else is a real failure.
      if [ "$rc" -ne 0 ] && [ "$rc" -ne 3 ]; then
        echo "protocol.sh: laguerre simulate failed on $family $n ($mode, exit status $rc)" >&2
        exit "$rc"
      fi
      python3 - "$dir/out.json" "$family" "$label" "$N" "$rc" "$cpu" >>"$dir/rows" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
family, mode, N, rc, cpu = sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]), float(sys.argv[6])
n = d["nodes"]
v = d.get("verify")
same = "-" if v is None else ("bit-exact" if "identical" in v else "DIFFERS")
status = "converged" if rc == 0 else "NOT converged"
waves = d["by_phase"].get("placed", {}).get("messages", 0) // (2 * d["edges"])  # one PlacedMsg per dart and wave
# Set-up: depth BFS, election, layout wave and its acknowledgements, shape and height broadcasts (relayed
# set-up messages of face vertices count as relays, not here).
setup = sum(d["by_phase"].get(t, {}).get("messages", 0) for t in ("depth", "election", "start", "wave", "shape", "height"))
print(family, n, mode, N, d["rounds"], d["iterations"], waves, d["messages_per_node_mean"], d["bytes_per_node_mean"],
      d["simulated_seconds"], d["wall_seconds"], cpu, d["events_per_second"], d["peak_memory_bytes"] / 1024 / n,
      status.replace(" ", "_"), same, setup / n)
PY
      tail -1 "$dir/rows" | awk '{printf "%-24s %7s %-15s %4s %6s %6s %6s %10.0f %10.1f %11.0f %9.2f %9.1f %8.1f %9.3g %8.2f %-13s %s\n",
        $1, $2, $3, $4, $5, $6, $7, $8, $17, $9, $10, $11, $12, $13, $14, $15, $16}' | sed 's/NOT_converged/NOT converged/'
     done
    done
  done
done
echo "growth of messages per node (converged rows, least squares in log-log):"
python3 - "$dir/rows" <<'PY'
import math, sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
groups = {}
for r in rows:
    if r[14] == "converged":
        groups.setdefault((r[0], r[2]), []).append((float(r[1]), float(r[7])))
for (family, mode), pts in sorted(groups.items()):
    if len(pts) < 2:
        print(f"  {family:<24} {mode:<15} (one size only)")
        continue
    xs = [math.log(n) for n, _ in pts]
    ys = [math.log(m) for _, m in pts]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    b = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
    a = math.exp(my - b * mx)
    print(f"  {family:<24} {mode:<15} msgs/node ≈ {a:.3g} · n^{b:.2f}  (sizes {', '.join(str(int(n)) for n, _ in pts)})")
PY
echo "load after: $(uptime)"
