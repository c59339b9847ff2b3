#!/usr/bin/env bash
# Thesis §5.4's question, measured: steps, Thurston-equivalent sweeps, rounds and messages per node to
# LPD/GLPD for plain Thurston, the local accelerations the network runs (chebyshev, local-superstep),
# Newton–Krylov in the network (newton-krylov; all four `laguerre simulate --accelerate`, every message
# simulated, sync mode, N = 1, links of constant 1 ms latency) and centralized Newton (`laguerre pack
# --accelerate newton`: Newton steps, no messages), on uniform random triangulations and uniform random
# 3-connected maps (`laguerre generate`). One table; figures are means over the seeds of a size.
#   tools/bench/acceleration.sh [--timeout SECONDS] [--seeds "50:5 500:2 5000:1"] [--modes "…"]
#                               [--skip "MODE:N …"] [--families "…"] [SIZES…]
# Defaults: sizes 50 500 5000, timeout 600 s per simulator run (a run that does not finish in time
# prints "timeout" and the central core::pack sweep count instead, if that finishes in time too),
# modes "plain chebyshev local-superstep newton-krylov newton"; --skip "plain:5000" prints "skipped"
# for that mode and size. Rows up to 500 nodes are checked bit for bit against core::pack (--verify).
# Columns: steps = Thurston sweeps (Newton steps for newton-krylov and newton); sweeps = Thurston-
# equivalent sweeps, the neighbour exchanges (newton-krylov: the radius exchange, one per CG iteration
# and one per line-search trial, from `laguerre pack --json`); cg = CG iterations; rounds = protocol
# rounds (layout + check + convergecast); hops = simulated time in link latencies (sequential message
# delays: set-up, exchanges, tree sums, layout waves); "greedy" is the share of 1000 sampled pairs
# delivered hop by hop by greedy power routing on the protocol's embedding.
# LAGUERRE_EXE=path uses that program instead of building the release preset with tools/bootstrap.sh.
set -euo pipefail
cd "$(dirname "$0")/../.."

timeout_s=600 seeds_spec="50:5 500:2 5000:1" modes="plain chebyshev local-superstep newton-krylov newton" skip="" sizes=()
families="uniform-triangulation uniform-three-connected"
while [ $# -gt 0 ]; do
  case "$1" in
    --timeout) timeout_s=$2; shift 2 ;;
    --seeds) seeds_spec=$2; shift 2 ;;
    --modes) modes=$2; shift 2 ;;
    --skip) skip=$2; shift 2 ;;
    --families) families=$2; shift 2 ;;
    -h|--help) sed -n '2,21p' "$0"; exit 0 ;;
    *) sizes+=("$1"); shift ;;
  esac
done
[ ${#sizes[@]} -eq 0 ] && sizes=(50 500 5000)

. tools/bench/common.sh
echo "# $(uptime)"
seeds_of() {
  local n=$1 s
  for s in $seeds_spec; do [ "${s%%:*}" = "$n" ] && { echo "${s#*:}"; return; }; done
  echo 1
}
printf '%-24s %5s %5s %-14s %6s %7s %7s %6s %8s %10s %11s %6s %7s %-5s %7s\n' family nodes seeds mode steps sweeps cg \
  rounds hops 'msgs/node' 'bytes/node' 'LPD' greedy '=core' wall_s
for family in $families; do
  for n in "${sizes[@]}"; do
    count=$(seeds_of "$n")
    for seed in $(seq 1 "$count"); do
      "$laguerre" generate "$family" -n "$n" --seed "$seed" --format edges -o "$dir/$family-$n-$seed.txt" 2>/dev/null
    done
    for mode in $modes; do
      if [[ " $skip " == *" $mode:$n "* ]]; then
        printf '%-24s %5s %5s %-14s %6s\n' "$family" "$n" "$count" "$mode" skipped
        continue
      fi
      : >"$dir/rows"
      for seed in $(seq 1 "$count"); do
        g="$dir/$family-$n-$seed.txt"
        if [ "$mode" = newton ]; then
          if timeout "$timeout_s" "$laguerre" pack "$g" --accelerate newton --json --no-picture >"$dir/out.json" 2>/dev/null ||
             [ $? -eq 3 ]; then
            python3 - "$dir/out.json" >>"$dir/rows" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))["packing"]
print("central", p["iterations"], "-", "-", "-", "-", "-", "-", p["local_ok"] == len(json.load(open(sys.argv[1]))["vertices"]), "-", "-", p["seconds"])
PY
          else
            echo "timeout" >>"$dir/rows"
          fi
          continue
        fi
        verify=(); [ "$n" -le 500 ] && verify=(--verify)
        start=$(date +%s.%N)
        if timeout "$timeout_s" "$laguerre" simulate "$g" --accelerate "$mode" --pairs 1000 --json "${verify[@]}" \
             >"$dir/out.json" 2>/dev/null || [ $? -eq 3 ]; then
          end=$(date +%s.%N)
          echo '{}' >"$dir/pack.json"
          if [ "$mode" = newton-krylov ]; then  # the exchange and CG counts, from the reference run
            timeout "$timeout_s" "$laguerre" pack "$g" --accelerate newton-krylov --json --no-picture >"$dir/pack.json" \
              2>/dev/null || true
          fi
          python3 - "$dir/out.json" "$start" "$end" "$dir/pack.json" "$mode" >>"$dir/rows" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
nk = (json.load(open(sys.argv[4])).get("packing") or {}).get("newton_krylov") or {}
verify = d.get("verify", "-")
same = "yes" if "identical" in str(verify) else ("-" if verify == "-" else "NO")
sweeps = nk.get("exchanges", "-") if sys.argv[5] == "newton-krylov" else d["iterations"]
print("sim", d["iterations"], sweeps, nk.get("cg_iterations", "-"), d["rounds"], d["simulated_seconds"] * 1000,
      d["messages_per_node_mean"], d["bytes_per_node_mean"], d["local_condition_holds"] == d["nodes"],
      d["delivered"] / max(1, d["packets"]), same, float(sys.argv[3]) - float(sys.argv[2]))
PY
        else
          # Too slow in the simulator: the sweep count of core::pack (the same iteration), if it finishes.
          if timeout "$timeout_s" "$laguerre" pack "$g" --accelerate "$mode" --json --no-picture >"$dir/out.json" 2>/dev/null; then
            python3 - "$dir/out.json" >>"$dir/rows" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))["packing"]
nk = p.get("newton_krylov") or {}
print("timeout-central", p["iterations"], nk.get("exchanges", p["iterations"]), nk.get("cg_iterations", "-"), "-", "-", "-", "-",
      p["status"] == "converged", "-", "-", p["seconds"])
PY
          else
            echo "timeout" >>"$dir/rows"
          fi
        fi
      done
      python3 - "$dir/rows" "$family" "$n" "$count" "$mode" "$timeout_s" <<'PY'
import sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip()]
family, n, count, mode, t = sys.argv[2:7]
def mean(i, fmt):
    v = [float(r[i]) for r in rows if len(r) > i and r[i] not in ("-",)]
    return fmt % (sum(v) / len(v)) if v and len(v) == len(rows) else "-"
kinds = {r[0] for r in rows}
if "timeout" in kinds:
    print("%-24s %5s %5s %-14s %6s   (a run did not finish in %s s)" % (family, n, count, mode, "timeout", t))
    sys.exit()
star = "*" if kinds == {"timeout-central"} else ""
lpd = "%d/%d" % (sum(r[8] == "True" for r in rows), len(rows))
same = ",".join(sorted({r[10] for r in rows}))
print("%-24s %5s %5s %-14s %6s %7s %7s %6s %8s %10s %11s %6s %7s %-5s %7s" % (
      family, n, count, mode, mean(1, "%.0f") + star, mean(2, "%.0f") + star, mean(3, "%.0f"), mean(4, "%.0f"),
      mean(5, "%.0f"), mean(6, "%.0f"), mean(7, "%.0f"), lpd, mean(9, "%.4f"), same, mean(11, "%.1f")))
PY
    done
  done
done
echo "# steps: Thurston sweeps, or Newton steps (newton-krylov in the network; newton central, no messages);"
echo "# sweeps: neighbour exchanges; * = simulator timed out, core::pack's count"
echo "# $(uptime)"
