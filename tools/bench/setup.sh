#!/usr/bin/env bash
# The packing protocol's set-up (depth BFS, election, layout wave, shape/height) per node, this build
# and, with --against EXE, an older `laguerre` side by side on the same graphs, run one after the
# other. One `laguerre simulate GRAPH --accelerate chebyshev -N 10 --max-iterations 1 --pairs 1 --json`
# per build and size on a Delaunay graph (`laguerre generate delaunay -n N --seed S`): the set-up
# messages by phase per node (depth = DepthMsg; election = ElectionMsg, i.e. the election's reports,
# ring and path and the depth BFS's settled / final tokens; wave = StartMsg + WaveMsg; shape = ShapeMsg
# + HeightMsg), then the whole run's simulated seconds and wall seconds (the protocol only: set-up,
# round 0 and one Thurston step; at these sizes the set-up is nearly all of it) and whether the
# circles equal core::pack bit for bit (--verify, up to --verify-to nodes). Last, per size, the
# ratios after/before of set-up messages per node, simulated time and wall time.
#   tools/bench/setup.sh [--against EXE] [--seed S] [--verify-to NODES] [SIZES…]
# Defaults: sizes 1000 10000 100000, seed 1, verify up to 10000 nodes. The load averages (uptime)
# are printed before and after: on a shared machine compare wall times from one run only.
# LAGUERRE_EXE=path uses that program as "this build" instead of building the release preset.
set -euo pipefail
cd "$(dirname "$0")/../.."

against="" seed=1 verify_to=10000 sizes=()
while [ $# -gt 0 ]; do
  case "$1" in
    --against) against=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    --verify-to) verify_to=$2; shift 2 ;;
    -h|--help) sed -n '2,16p' "$0"; exit 0 ;;
    *) sizes+=("$1"); shift ;;
  esac
done
[ ${#sizes[@]} -eq 0 ] && sizes=(1000 10000 100000)
if [ -n "$against" ] && [ ! -x "$against" ]; then
  echo "setup.sh: --against '$against' is not an executable" >&2
  exit 2
fi

. tools/bench/common.sh
echo "load before: $(uptime)"
builds=("after:$laguerre"); [ -n "$against" ] && builds=("before:$against" "after:$laguerre")
printf '%8s %-7s %8s %9s %8s %8s %11s %8s %8s %-10s\n' nodes build depth election wave shape setup/node sim_s wall_s '=core'
: >"$dir/rows"
for n in "${sizes[@]}"; do
  g="$dir/delaunay-$n.txt"
  "$laguerre" generate delaunay -n "$n" --seed "$seed" -o "$g" >/dev/null 2>&1
  verify=(); [ "$n" -le "$verify_to" ] && verify=(--verify)
  for b in "${builds[@]}"; do
    label=${b%%:*} exe=${b#*:}
    rc=0
    "$exe" simulate "$g" --accelerate chebyshev -N 10 --max-iterations 1 --pairs 1 --json "${verify[@]}" \
      >"$dir/out.json" 2>/dev/null || rc=$?
    if [ "$rc" -ne 0 ] && [ "$rc" -ne 3 ]; then  # 3: not converged (one step only), as expected
      echo "setup.sh: $exe simulate failed on $n nodes (exit status $rc)" >&2
      exit "$rc"
    fi
    python3 - "$dir/out.json" "$label" >>"$dir/rows" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
n, ph = d["nodes"], d["by_phase"]
m = lambda *ts: sum(ph.get(t, {}).get("messages", 0) for t in ts) / n
v = d.get("verify")
same = "-" if v is None else ("bit-exact" if "identical" in v else "DIFFERS")
print(n, sys.argv[2], m("depth"), m("election"), m("start", "wave"), m("shape", "height"),
      m("depth", "election", "start", "wave", "shape", "height"), d["simulated_seconds"], d["wall_seconds"], same)
PY
    tail -1 "$dir/rows" | awk '{printf "%8s %-7s %8.1f %9.2f %8.2f %8.2f %11.1f %8.3f %8.2f %-10s\n", $1, $2, $3, $4, $5, $6, $7, $8, $9, $10}'
  done
done
if [ -n "$against" ]; then
  echo "after / before:"
  awk '{ k = $1; if ($2 == "before") { bs[k] = $7; bt[k] = $8; bw[k] = $9 } else if (k in bs)
           printf "%8s  set-up msgs/node %.3f  simulated %.3f  wall %.3f\n", k, $7 / bs[k], $8 / bt[k], $9 / bw[k] }' "$dir/rows"
fi
echo "load after: $(uptime)"
