#!/usr/bin/env bash
# The diagram library (issue 5) at 10^3 … 10^6 sites: CGAL's raw Regular_triangulation_2 insertion
# (anchor: about 1.0 s for 10^6 sites on this machine kind), our Voronoi and power diagram facades
# (triangulation + clipped cells + edges), CGAL's Regular_triangulation_3 of the lifted spheres alone,
# and the whole Möbius and multiplicatively weighted constructions (lifting, vertices, edges, cells).
#   tools/bench/diagrams.sh [--quick|--huge] [BUILD_DIR]
# --quick: sizes up to 10^4 (a minute); default: up to 10^6 except the Möbius kinds (up to 10^5);
# --huge: everything at 10^6 as well. BUILD_DIR defaults to build/release (configured with
# -DLAGUERRE_BUILD_BENCHMARKS=ON and built here). Times are CPU times of one thread.
set -euo pipefail
cd "$(dirname "$0")/../.."
mode=default build=build/release
for a in "$@"; do
  case "$a" in
    --quick) mode=quick ;;
    --huge) mode=huge ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) build=$a ;;
  esac
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
"$build/tools/bench/bench_diagrams" --benchmark_filter="$filter" --benchmark_counters_tabular=true
