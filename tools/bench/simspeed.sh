#!/usr/bin/env bash
# Simulator speed and memory of the packing protocol, one program against another in one run, next
# to the kernel's PHOLD rate at the same node count: per size, one `laguerre simulate` run per
# program on the same graph (same arguments), printing events, CPU seconds, events per CPU second,
# peak RSS per node (/usr/bin/time; graph and program included), the PHOLD rate of phold_laguerre
# with as many LPs as nodes (events per CPU second, best of --repeat), the ratio PHOLD / protocol,
# and whether the two programs' JSON results are equal (timing and memory fields aside).
#   tools/bench/simspeed.sh [--before EXE] [--family F] [-N STEPS] [--max-iterations K]
#                           [--cpu-limit SECONDS] [--repeat R] [--seed S] [SIZES…]
# Defaults: sizes 10000; family delaunay (`laguerre generate`); chebyshev, N = max(1, n/1000), 10 pairs;
# --before: no second program (one row per size); --cpu-limit: none (with a limit, `ulimit -t`
# stops a run after that much CPU: its row gives the peak memory so far and no result, e.g. to
# measure the set-up's memory at 10^5 nodes in bounded time).
# LAGUERRE_EXE=path is the program under test (else the release preset's build, tools/bootstrap.sh);
# PHOLD_EXE=path the phold_laguerre program (else build/release/tools/bench/phold_laguerre, built
# with the release preset if missing).
set -euo pipefail
cd "$(dirname "$0")/../.."

before="" family=delaunay steps="" max_iterations="" cpu_limit="" repeat=3 seed=42 sizes=()
while [ $# -gt 0 ]; do
  case "$1" in
    --before) before=$2; shift 2 ;;
    --family) family=$2; shift 2 ;;
    -N) steps=$2; shift 2 ;;
    --max-iterations) max_iterations=$2; shift 2 ;;
    --cpu-limit) cpu_limit=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    -*) echo "simspeed.sh: unknown option $1" >&2; exit 2 ;;
    *) sizes+=("$1"); shift ;;
  esac
done
[ ${#sizes[@]} -eq 0 ] && sizes=(10000)

. tools/bench/common.sh
phold=${PHOLD_EXE:-build/release/tools/bench/phold_laguerre}
if [ ! -x "$phold" ]; then
  cmake --preset release >/dev/null
  cmake --build build/release --target phold_laguerre -j2 >&2
fi

echo "load before: $(uptime)"
printf '%-8s %-7s %11s %8s %10s %9s %10s %7s %s\n' program nodes events cpu_s events/cpu KiB/node phold/cpu ratio result
for n in "${sizes[@]}"; do
  g="$dir/$family-$n.txt"
  format=coords; case "$family" in uniform-*) format=edges ;; esac
  "$laguerre" generate "$family" -n "$n" --seed "$seed" --format "$format" -o "$g" 2>/dev/null
  N=${steps:-$(( n / 1000 ))}; [ "$N" -lt 1 ] && N=1
  args=(simulate "$g" --accelerate chebyshev -N "$N" --pairs 10 --json)
  [ -n "$max_iterations" ] && args+=(--max-iterations "$max_iterations")
  # PHOLD with as many LPs as nodes: the best events per CPU second (field 8) of $repeat runs.
  rate=0
  for _ in $(seq "$repeat"); do
    r=$("$phold" --lps "$n" --events 10000000 | awk '{print $8}')
    rate=$(awk -v a="$rate" -v b="$r" 'BEGIN {print (b > a) ? b : a}')
  done
  programs=(); [ -n "$before" ] && programs+=("before=$before"); programs+=("after=$laguerre")
  for entry in "${programs[@]}"; do
    name=${entry%%=*} exe=${entry#*=}
    rc=0
    ( [ -n "$cpu_limit" ] && ulimit -t "$cpu_limit"
      exec /usr/bin/time -f '%U %S %M' -o "$dir/time" "$exe" "${args[@]}" >"$dir/$name.json" 2>/dev/null ) || rc=$?
    # The last line (GNU time first writes "Command exited with non-zero status …" when it did).
    read -r user sys rss_kib < <(tail -1 "$dir/time") || { user=0 sys=0 rss_kib=0; }
    python3 - "$dir/$name.json" "$n" "$name" "$user" "$sys" "$rss_kib" "$rate" "$rc" "$dir/before.json" <<'PY'
import json, os, sys
path, n, name, user, sys_s, rss, rate, rc, ref = sys.argv[1:]
n, cpu, rss, rate, rc = int(n), float(user) + float(sys_s), float(rss), float(rate), int(rc)
volatile = {"wall_seconds", "events_per_second", "peak_memory_bytes"}
def strip(d):
    if isinstance(d, dict):
        return {k: strip(v) for k, v in d.items() if k not in volatile}
    if isinstance(d, list):
        return [strip(v) for v in d]
    return d
try:
    d = json.load(open(path))
except (OSError, ValueError):
    d = None
events = d["events"] if d and "events" in d else 0
result = "stopped (exit status %d)" % rc if d is None else ("converged" if rc == 0 else "exit status %d" % rc)
if d is not None and name == "after" and os.path.exists(ref):
    try:
        same = strip(json.load(open(ref))) == strip(d)
        result += ", same JSON as before" if same else ", JSON DIFFERS from before"
    except ValueError:
        pass
per_cpu = events / cpu if cpu > 0 and events else 0
ratio = "%6.1fx" % (rate / per_cpu) if per_cpu else "     -"
print("%-8s %-7d %11d %8.1f %10.3g %9.2f %10.3g %7s %s" % (name, n, events, cpu, per_cpu, rss / n, rate, ratio, result))
PY
  done
done
echo "load after: $(uptime)"
