#!/usr/bin/env bash
# The diagram library (issue 5) at 10^3 … 10^6 sites: CGAL's raw Regular_triangulation_2 insertion
# (anchor: about 1.0 s for 10^6 sites on this machine kind), our Voronoi and power diagram facades
# (triangulation + clipped cells + edges), CGAL's Regular_triangulation_3 of the lifted spheres alone,
# and the whole Möbius and multiplicatively weighted constructions (lifting, vertices, edges, cells).
#   tools/bench/diagrams.sh [--quick|--huge] [--before BENCH_EXE] [BUILD_DIR]
# --quick: sizes up to 10^4 (a minute); default: up to 10^6 except the Möbius kinds (up to 10^5);
# --huge: everything at 10^6 as well. BUILD_DIR defaults to build/release (configured with
# -DLAGUERRE_BUILD_BENCHMARKS=ON and built here). Times are CPU times of one thread.
# --before BENCH_EXE: the Möbius and multiplicatively weighted rows only, run by another build's
# bench_diagrams (e.g. a copy from before a change) and by this one, alternately, side by side: CPU
# ms of each, the ratio this/before, and the vertex and edge counts of each.
set -euo pipefail
cd "$(dirname "$0")/../.."
mode=default build=build/release before=""
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) mode=quick ;;
    --huge) mode=huge ;;
    --before) before=$2; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) build=$1 ;;
  esac
  shift
done
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DLAGUERRE_WERROR=ON -DLAGUERRE_BUILD_BENCHMARKS=ON >/dev/null
else
  cmake -S . -B "$build" -DLAGUERRE_BUILD_BENCHMARKS=ON >/dev/null
fi
cmake --build "$build" --target bench_diagrams -j2 >/dev/null
case "$mode" in
  quick) filter='/(1000|10000)$' ;;
  huge) filter='.' ;;
  *) filter='^BM_(CgalRegularTriangulation2|VoronoiDiagram|PowerDiagram|CgalRegularTriangulation3Lifted)/|^BM_(MobiusDiagram|MultiplicativelyWeighted)/(1000|10000|100000)$' ;;
esac
if [ -z "$before" ]; then
  "$build/tools/bench/bench_diagrams" --benchmark_filter="$filter" --benchmark_counters_tabular=true
  exit 0
fi
case "$mode" in
  quick) sizes="1000 10000" ;;
  huge) sizes="1000 10000 100000 1000000" ;;
  *) sizes="1000 10000 100000" ;;
esac
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for kind in MobiusDiagram MultiplicativelyWeighted; do
  for n in $sizes; do
    for side in before after; do
      exe="$build/tools/bench/bench_diagrams"
      [ "$side" = before ] && exe=$before
      "$exe" --benchmark_filter="^BM_$kind/$n\$" --benchmark_format=json > "$out/$kind-$n-$side.json"
    done
  done
done
python3 - "$out" $sizes <<'PY'
import json, sys
out, sizes = sys.argv[1], sys.argv[2:]
print(f"{'benchmark':<30}{'n':>9}{'before ms':>12}{'after ms':>12}{'ratio':>8}{'vertices before/after':>26}{'edges before/after':>24}")
for kind in ("MobiusDiagram", "MultiplicativelyWeighted"):
    for n in sizes:
        b, a = (json.load(open(f"{out}/{kind}-{n}-{s}.json"))["benchmarks"][0] for s in ("before", "after"))
        ms = lambda r: r["cpu_time"] * {"ns": 1e-6, "us": 1e-3, "ms": 1, "s": 1e3}[r["time_unit"]]
        print(f"{'BM_' + kind:<30}{n:>9}{ms(b):>12.1f}{ms(a):>12.1f}{ms(a) / ms(b):>8.2f}"
              f"{'%d/%d' % (b['vertices'], a['vertices']):>26}{'%d/%d' % (b['edges'], a['edges']):>24}")
PY
