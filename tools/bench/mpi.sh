#!/usr/bin/env bash
# The MPI parallel kernel measured (issue 13 §3): PHOLD on a torus at 10^5 and 10^6 nodes, the
# sequential Simulator, then the parallel kernel on 1 and 2 ranks (this machine has 2 cores), with
# events/s, windows, copies exchanged per window, time in events vs in synchronisation, peak memory
# per rank, the exchange latency τ and the coupling factor λ = L·E/(τ·P). The trace hashes of the
# 10^5 runs are printed side by side: they must be equal (the parallel run is the sequential one).
# Then the packing protocol (`laguerre simulate`, a Delaunay graph of each --protocol size, the set-up
# then --steps Thurston steps, constant 1 ms latency, one forwarded pair) sequentially and on the same
# ranks: events, wall, CPU seconds of the whole command (user + system, all ranks), peak memory of the
# protocol phase (the largest over the ranks), on more than one rank the kernel's windows, copies
# exchanged per window, cut links, and per rank (lists, rank 0 first) nodes, events, seconds in events
# and in synchronization and peak memory (`simulate --json`'s "mpi"), and a hash of the JSON without
# its wall-clock and kernel fields (equal on every line of a size: the same run).
#   tools/bench/mpi.sh [--preset release] [--sizes "316 1000"] [--until "50 5"] [--ranks "1 2"]
#                      [--protocol "10000 1000000"] [--steps "50 5"] [--baseline DIR]
# --sizes are torus sides (316² = 99 856, 1000² = 10^6 nodes); --until the simulated seconds of each;
# --protocol the protocol's graph sizes, --steps the Thurston steps of each (the last one repeats);
# --protocol 0 (or "") skips the protocol runs, --sizes "" the PHOLD ones. --baseline DIR holds the phold_mpi and laguerre programs of
# another commit (e.g. copied from main's build): every run is then made with it too, right before
# this tree's, and each line starts with build=baseline or build=this.
set -euo pipefail
cd "$(dirname "$0")/../.."
preset=release sides="316 1000" untils="50 5" ranks="1 2" protocols=10000 steps=50 baseline=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --preset) preset="$2"; shift 2 ;;
    --sizes) sides="$2"; shift 2 ;;
    --until) untils="$2"; shift 2 ;;
    --ranks) ranks="$2"; shift 2 ;;
    --protocol) protocols="$2"; shift 2 ;;
    --steps) steps="$2"; shift 2 ;;
    --baseline) baseline="$2"; shift 2 ;;
    *) echo "mpi.sh: unknown argument '$1' (expected --preset, --sizes, --until, --ranks, --protocol, --steps or --baseline)" >&2
       exit 2 ;;
  esac
done
if [[ -n "$baseline" && ! ( -x "$baseline/phold_mpi" && -x "$baseline/laguerre" ) ]]; then
  echo "mpi.sh: --baseline $baseline has no executable phold_mpi and laguerre" >&2
  exit 2
fi
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" --target phold_mpi laguerre >/dev/null
builds=(this) dirs=("build/$preset/tools/bench")
laguerres=("build/$preset/tools/laguerre")
if [[ -n "$baseline" ]]; then builds=(baseline this) dirs=("$baseline" "${dirs[0]}") laguerres=("$baseline/laguerre" "${laguerres[0]}"); fi
# CI and this machine run as root, which OpenMPI refuses unless told.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "# $(date -u +%FT%TZ) $(git rev-parse --short HEAD) load: $(uptime | sed 's/.*load average: //') cores: $(nproc)"
read -r -a side_list <<<"$sides"
read -r -a until_list <<<"$untils"
out=$(mktemp) work=$(mktemp -d)
trap 'rm -rf "$out" "$work"' EXIT
for i in "${!side_list[@]}"; do
  side=${side_list[$i]} until=${until_list[$i]:-${until_list[-1]}}
  trace=$([[ $side -le 400 ]] && echo 1 || echo 0)  # the merged trace costs records on every rank
  for b in "${!builds[@]}"; do
    exe="${dirs[$b]}/phold_mpi" tag="build=${builds[$b]}"
    "$exe" --side "$side" --until "$until" --sequential 1 --trace "$trace" | sed "s/^/$tag /" | tee -a "$out"
    for np in $ranks; do
      mpirun -np "$np" --oversubscribe --bind-to none "$exe" --side "$side" --until "$until" --trace "$trace" |
        sed "s/^/$tag /" | tee -a "$out"
    done
  done
done
read -r -a protocol_list <<<"$protocols"
read -r -a steps_list <<<"$steps"
protocol_line() {  # tag, ranks, JSON file, /usr/bin/time file
  python3 - "$@" <<'PY'
import hashlib, json, sys
tag, ranks, path, timing = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4]
d = json.load(open(path))
user, system = (float(x) for x in open(timing).read().split()[-2:])
peak = d.pop("peak_memory_bytes"); wall = d.pop("wall_seconds"); d.pop("events_per_second"); d.pop("mpi_ranks", None)
mpi = d.pop("mpi", None)  # the parallel kernel's windows and timings (not part of the result)
same = hashlib.sha256(json.dumps(d, sort_keys=True).encode()).hexdigest()[:16]
kernel = ""
if mpi:
    w = max(mpi["windows"], 1)
    per_rank = lambda key, f: ",".join(f(x) for x in mpi[key])
    kernel = (f" windows={mpi['windows']} copies_per_window={mpi['remote_copies'] / w:.1f} cut_links={mpi['cut_links']} "
              f"events_s_max_rank={max(mpi['event_seconds']):.3f} sync_s_max_rank={max(mpi['sync_seconds']):.3f} "
              f"rank_nodes={per_rank('nodes', str)} rank_events={per_rank('events', str)} "
              f"rank_events_s={per_rank('event_seconds', lambda x: f'{x:.1f}')} "
              f"rank_sync_s={per_rank('sync_seconds', lambda x: f'{x:.1f}')} "
              f"rank_peak_mb={per_rank('peak_memory_bytes', lambda x: f'{x / 1e6:.0f}')}")
print(f"{tag} mode=protocol ranks={ranks} nodes={d['nodes']} steps={d['iterations']} events={d['events']} "
      f"wall_s={wall:.3f} events_per_s={d['events'] / wall:.0f} cpu_s={user + system:.1f} "
      f"peak_mb_max_rank={peak / 1e6:.1f}{kernel} result={same}")
PY
}
for i in "${!protocol_list[@]}"; do
  protocol=${protocol_list[$i]} step=${steps_list[$i]:-${steps_list[-1]}}
  [[ "$protocol" -gt 0 ]] || continue
  graph="$work/delaunay-$protocol.txt"
  "${laguerres[-1]}" generate delaunay -n "$protocol" --seed 1 -o "$graph" >/dev/null 2>&1
  options=(--max-iterations "$step" --pairs 1 --json)
  for b in "${!builds[@]}"; do
    tag="build=${builds[$b]}" lag="${laguerres[$b]}"
    # 3 (not converged in the steps given) is expected; mpirun then talks on stderr
    rc=0; /usr/bin/time -f "%U %S" -o "$work/time" "$lag" simulate "$graph" "${options[@]}" >"$work/out.json" || rc=$?
    [[ $rc -eq 0 || $rc -eq 3 ]] || { echo "mpi.sh: laguerre simulate failed (exit status $rc)" >&2; exit 1; }
    protocol_line "$tag" sequential "$work/out.json" "$work/time"
    for np in $ranks; do
      rc=0; /usr/bin/time -f "%U %S" -o "$work/time" mpirun -np "$np" --oversubscribe --bind-to none "$lag" simulate \
        "$graph" "${options[@]}" >"$work/out.json" 2>"$work/err" || rc=$?
      [[ $rc -eq 0 || $rc -eq 3 ]] || { cat "$work/err" >&2; echo "mpi.sh: mpirun laguerre simulate failed ($rc)" >&2; exit 1; }
      protocol_line "$tag" "$np" "$work/out.json" "$work/time"
    done
  done
done
# The scaling model (README, "Scaling out"), fitted to this run: c_e = CPU ns per event of the
# smallest sequential run; k from the METIS cut of the 2-rank runs (cut fraction = k·sqrt(P/n));
# a remote copy costs c_m = c_e more (encode, exchange, decode); τ(P) = TAU0·log2 P + TAU1·P
# (small-message MPI_Alltoall on a cluster network: an assumption, not measured here; set TAU0_US,
# TAU1_US from the cluster's osu_alltoall). PHOLD with one message per node, mean delay 1.1 s,
# lookahead 0.1 s: m = n/11 events per window in all, m/P per rank, the slowest of P ranks doing
# m/P + sqrt(2 (m/P) ln P) (Poisson imbalance).
awk -v tau0="${TAU0_US:-3}" -v tau1="${TAU1_US:-0.3}" '
  function field(line, key,   i, n, kv) { n = split(line, kv, " "); for (i = 1; i <= n; ++i) if (index(kv[i], key "=") == 1) return substr(kv[i], length(key) + 2); return "" }
  !/build=this/ { next }  # the model is fitted to this tree
  /mode=sequential/ && ce == "" { ce = field($0, "ns_per_event_cpu") * 1e-9 }
  /mode=parallel ranks=2/ { nodes = field($0, "nodes"); cut = field($0, "cut_links"); ks += (cut / (4 * nodes)) / sqrt(2 / nodes); kn++ }
  END {
    if (ce == "" || kn == 0) { print "# model: needs a sequential run and a 2-rank run"; exit }
    k = ks / kn
    printf "# model: c_e = %.0f ns/event (CPU, sequential), k = %.2f (cut fraction = k*sqrt(P/n)), tau(P) = %g us*log2(P) + %g us*P\n", ce * 1e9, k, tau0, tau1
    printf "# predicted PHOLD speed-up S(P) and coupling lambda = (n/11)*c_e/tau(P)\n"
    printf "# %-6s", "ranks"; split("1e6 1e7 1e8", ns, " "); for (j = 1; j <= 3; ++j) printf " | n=%-4s S     lambda", ns[j]; printf "\n"
    split("2 8 16 64 256 1024", ps, " ")
    for (i = 1; i <= 6; ++i) {
      P = ps[i]; tau = (tau0 * log(P) / log(2) + tau1 * P) * 1e-6
      printf "  %-6d", P
      for (j = 1; j <= 3; ++j) {
        n = ns[j] + 0; m = n / 11; mp = m / P
        t1 = ce * m
        tp = ce * (mp + sqrt(2 * mp * log(P))) + tau + ce * mp * k * sqrt(P / n)
        printf " | %10.1f %8.1f", t1 / tp, m * ce / tau
      }
      printf "\n"
    }
  }' "$out"
