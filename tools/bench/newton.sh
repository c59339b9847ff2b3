#!/usr/bin/env bash
# Newton's method on the angle sums (`laguerre pack --accelerate newton`) with its three linear
# solvers side by side in one run: lu (the original: finite-difference Jacobian in log h, Eigen's
# SparseLU), cholesky (closed-form SPD Jacobian in u = log tanh(h/2), CHOLMOD supernodal) and pcg
# (incomplete-Cholesky conjugate gradients), on random Delaunay triangulations and uniform random
# triangulations, stopped at LPD.
#   tools/bench/newton.sh [--huge] [--solvers "lu cholesky pcg"] [--families "delaunay uniform-triangulation"]
#                         [--layouts "frames"] [--arithmetics "binary64"] [--termination layout] [--pairs N]
#                         [--max-steps K] [--time-limit S] [--blas-dir DIR] [--seed S] [SIZES…]
# Defaults: sizes 10000 100000; --huge adds 1000000 (the lu solver is skipped there: ~40 s per step).
# Per row: steps as iterations/improving Newton steps (an iteration whose Newton step cannot improve is
# a plain sweep; capped at --max-steps, default 60), status (converged / iteration_cap / precision_loss, never hidden), vertices
# with LPD, smallest Euclidean radius, layout (`--layouts "wave frames"` runs both side by side;
# docs/precision.md), its precision status and resolution (smallest r / ulp of the circle's
# coordinates: the stored doubles are 8 bytes per coordinate), wall and CPU seconds inside core::pack (CPU time is the figure
# that survives a loaded machine), wall seconds of the whole command
# (reading and checking the graph, writing the JSON) and its peak RSS (/usr/bin/time). Then the growth
# exponents of steps and pack time between successive sizes (t ∝ n^a).
# Columns read_s (the command's wall time outside core::pack: reading and checking the graph, writing
# the JSON) and phases (core::pack's wall seconds by phase, packing.phase_seconds: Jacobian assembly /
# factorization and solve / line search / layouts / LPD checks; sweeps and set-up are not shown).
# --arithmetics "binary64 mixed binary128" runs each layout arithmetic side by side (mixed with the
# frames only; the layout column then reads frames/mixed), --termination passes pack's --termination
# (radius-only: layouts only once the angle sums are near 2π), --pairs N routes N sampled pairs by
# greedy power after each pack on the coordinates LPD was decided on (column routed: delivered/pairs
# and bytes per coordinate).
# --time-limit S passes `--time-limit S` to pack (status time_limit when it is hit). --blas-dir DIR
# puts DIR first on LD_LIBRARY_PATH for the pack runs, e.g. the directory of an unpacked
# libopenblas0-pthread (`apt-get download libopenblas0-pthread && dpkg -x …`: its libblas.so.3 then
# serves CHOLMOD without changing the system's libblas alternative); the header names the libblas
# the program loads.
# --seed S: the generator seed of the graphs (default 42; the README's 10^6 table uses 1).
# Inputs are cached in $LAGUERRE_BENCH_CACHE (default /tmp/laguerre-bench-newton): a 10^6 Delaunay
# triangulation takes about a minute to generate. OPENBLAS_NUM_THREADS and OMP_NUM_THREADS default to 1
# (a shared 2-core machine: spinning BLAS threads cost more than they bring here).
# LAGUERRE_EXE=path uses that program instead of building it with tools/bootstrap.sh.
set -euo pipefail
cd "$(dirname "$0")/../.."

solvers="lu cholesky pcg" families="delaunay uniform-triangulation" layouts=frames max_steps=60 huge=0 sizes=()
time_limit=() blas_dir="" seed=42 arithmetics=binary64 termination=layout pairs=()
while [ $# -gt 0 ]; do
  case "$1" in
    --huge) huge=1; shift ;;
    --solvers) solvers=$2; shift 2 ;;
    --families) families=$2; shift 2 ;;
    --layouts) layouts=$2; shift 2 ;;
    --arithmetics) arithmetics=$2; shift 2 ;;
    --termination) termination=$2; shift 2 ;;
    --pairs) pairs=(--pairs "$2" --seed 7); shift 2 ;;
    --max-steps) max_steps=$2; shift 2 ;;
    --time-limit) time_limit=(--time-limit "$2"); shift 2 ;;
    --blas-dir) blas_dir=$2; shift 2 ;;
    --seed) seed=$2; shift 2 ;;
    -h|--help) awk 'NR > 1 && /^#/ {print; next} NR > 1 {exit}' "$0"; exit 0 ;;
    *) sizes+=("$1"); shift ;;
  esac
done
[ ${#sizes[@]} -eq 0 ] && sizes=(10000 100000)
[ "$huge" -eq 1 ] && sizes+=(1000000)
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1} OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}

if [ -n "${LAGUERRE_EXE:-}" ]; then
  laguerre=$LAGUERRE_EXE
else
  tools/bootstrap.sh --preset release --target laguerre >/dev/null
  laguerre=build/release/tools/laguerre
fi
cache=${LAGUERRE_BENCH_CACHE:-/tmp/laguerre-bench-newton}
mkdir -p "$cache"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

if [ -n "$blas_dir" ]; then
  [ -e "$blas_dir/libblas.so.3" ] || { echo "newton.sh: --blas-dir $blas_dir has no libblas.so.3" >&2; exit 2; }
  export LD_LIBRARY_PATH="$blas_dir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
blas=$(ldd "$laguerre" | awk '/libblas/ {print $3}')
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(getconf _NPROCESSORS_ONLN) cores, load:$(uptime | sed 's/.*load average://'), OPENBLAS_NUM_THREADS=$OPENBLAS_NUM_THREADS, libblas $(readlink -f "$blas")"
printf '%-22s %8s %-9s %-16s %7s %-15s %9s %10s %-16s %9s %9s %9s %9s %7s %-11s %s\n' family n solver layout steps status LPD min_radius precision pack_s pack_cpu_s wall_s peak_MiB read_s routed 'phases(jac/solve/ls/layout/checks)'
rows=$dir/rows.tsv
: > "$rows"
for family in $families; do
  for n in "${sizes[@]}"; do
    # Delaunay with its coordinates (the embedding is read from them); the uniform family has none, and
    # its edge list is embedded by Boyer–Myrvold when it is read, minutes at 10^6 (in wall_s, not pack_s).
    format=edges; [ "$family" = delaunay ] && format=coords
    graph=$cache/$family-$n-seed$seed.$format
    [ -s "$graph" ] || "$laguerre" generate "$family" -n "$n" --seed "$seed" --format "$format" -o "$graph" --force >/dev/null 2>&1
    for solver in $solvers; do
     for layout in $layouts; do
      for arith in $arithmetics; do
      if [ "$solver" = lu ] && [ "$n" -ge 1000000 ]; then continue; fi
      if [ "$arith" = mixed ] && [ "$layout" != frames ]; then continue; fi
      label=$layout; [ "$arith" != binary64 ] && label=$layout/$arith
      rc=0
      /usr/bin/time -f '%e %M' -o "$dir/time" "$laguerre" pack "$graph" --accelerate newton --newton-solver "$solver" \
        --layout "$layout" --layout-arithmetic "$arith" --termination "$termination" --max-iterations "$max_steps" \
        "${time_limit[@]}" "${pairs[@]}" --no-picture -o "$dir/out" --force > "$dir/log" 2>&1 || rc=$?
      # Exit status 3: not converged (cap, time limit or precision loss), reported in the row; anything else fails.
      if [ "$rc" -ne 0 ] && [ "$rc" -ne 3 ]; then
        echo "newton.sh: laguerre pack failed on $graph with $solver (exit status $rc)" >&2
        cat "$dir/log" >&2
        exit "$rc"
      fi
      python3 - "$dir/out.json" "$dir/time" "$family" "$n" "$solver" "$label" >> "$rows" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
p = doc["packing"]
rt = doc.get("routing")
routed = f"{rt['delivered']}/{rt['pairs']}@{rt['bytes_per_coordinate']}B" if rt else "-"
wall, peak_kib = open(sys.argv[2]).read().split()[-2:]
pr = p["precision"]
ph = p["phase_seconds"]
phases = "/".join(f"{ph[k]:.1f}" for k in ("jacobian", "solve", "line_search", "layout", "checks"))
print("\t".join([sys.argv[3], sys.argv[4], sys.argv[5], f"{p['iterations']}/{p['accelerated_jumps']}", p["status"], str(p["local_ok"]),
                 f"{p['smallest_radius']:.3g}", f"{p['seconds']:.2f}", f"{p['cpu_seconds']:.2f}", wall,
                 f"{int(peak_kib) / 1024:.0f}", sys.argv[6], f"{pr['status']}:{pr['resolution']:.1e}",
                 f"{float(wall) - p['seconds']:.1f}", phases, routed]))
PY
      tail -n 1 "$rows" | awk -F'\t' '{printf "%-22s %8s %-9s %-16s %7s %-15s %9s %10s %-16s %9s %9s %9s %9s %7s %-11s %s\n", $1,$2,$3,$12,$4,$5,$6,$7,$13,$8,$9,$10,$11,$14,$16,$15}'
      done
     done
    done
  done
done

python3 - "$rows" <<'PY'
import math, sys
rows = [l.rstrip("\n").split("\t") for l in open(sys.argv[1]) if l.strip()]
by = {}
for r in rows:
    by.setdefault((r[0], r[2] + " " + r[11]), []).append((int(r[1]), int(r[3].split("/")[0]), float(r[8]), r[4]))
print("\n# growth between successive sizes: steps and pack CPU time ~ n^a (converged rows only)")
for (family, solver), pts in sorted(by.items()):
    pts.sort()
    for (n1, s1, t1, st1), (n2, s2, t2, st2) in zip(pts, pts[1:]):
        if st1 != "converged" or st2 != "converged" or t1 <= 0:
            continue
        k = math.log(n2 / n1)
        print(f"{family:<22} {solver:<16} {n1:>8} -> {n2:<8} steps {s1:>3} -> {s2:<3} (a = {math.log(s2 / s1) / k:5.2f})"
              f"   pack CPU time a = {math.log(t2 / t1) / k:5.2f}")
sides = {}
for r in rows:
    sides.setdefault((r[0], r[1], r[11]), {})[r[2]] = float(r[8])
print("\n# pack CPU-time ratios against lu, same family, size and layout")
for (family, n, layout), t in sorted(sides.items(), key=lambda x: (x[0][0], int(x[0][1]), x[0][2])):
    if "lu" in t:
        print(f"{family:<22} {n:>8} {layout:<7} " + "  ".join(f"lu/{s} = {t['lu'] / v:5.2f}" for s, v in t.items() if s != "lu" and v > 0))
PY
echo "# end $(date -u '+%H:%M UTC'), load:$(uptime | sed 's/.*load average://')"
