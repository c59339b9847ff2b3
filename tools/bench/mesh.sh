#!/usr/bin/env bash
# Anisotropic meshing speed and quality on the shock-layer field in the unit square (issue 6), side by
# side with the anchor the issue gives for mmg2d (a metric-based remesher with no guarantee; not in
# Debian, so its row is the published figure for this machine kind, not a run).
#   tools/bench/mesh.sh [--quick]     (--quick: the three smaller sizes and the two smaller Voronoi rows)
# The field is the shock layer shock:0.002:0.05:0.03:0.5 (sizes 0.002 across the layer at x = 0.5,
# 0.05 elsewhere); --size-bound 1, 0.25, 0.08 and 0.05 give about 4.5·10^3, 8·10^3, 5·10^4 and 10^5
# vertices (the distortion bound γ₀ = 1.5 alone already forces a few thousand vertices into that
# layer), and a ten times thicker layer, shock:0.02:0.2:0.1:0.5, gives the 10^3 row. Quality is
# measured in the metric of every vertex of each triangle (the worst is kept).
# A second table times the Voronoi refiner (thesis Part II, `--algorithm voronoi`) with its anisotropic
# diagram updated across rounds (the default) and rebuilt every round (`--rebuild-diagram`, the former
# path), CPU seconds of the process (/usr/bin/time: the machine is shared), and checks that both wrote
# the same mesh byte for byte.
set -euo pipefail
cd "$(dirname "$0")/../.."
source tools/bench/common.sh
field="shock:0.002:0.05:0.03:0.5"
thick="shock:0.02:0.2:0.1:0.5"
runs=("$thick 1" "$field 1" "$field 0.25" "$field 0.08" "$field 0.05")
[ "${1:-}" = "--quick" ] && runs=("$thick 1" "$field 1" "$field 0.25")
printf '%-12s %9s %9s %10s %12s %9s %9s %9s %10s\n' run vertices triangles seconds vertices/s \
  min_angle p5_angle max_rho max_gamma
echo "fields: $field (thin layer), $thick (thick layer)"
for run in "${runs[@]}"; do
  read -r metric bound <<<"$run"
  label=$([ "$metric" = "$thick" ] && echo "thick,$bound" || echo "thin,$bound")
  "$laguerre" mesh square --metric "$metric" --size-bound "$bound" -o "$dir/m" --force --no-picture --json > "$dir/r.json" || true
  python3 - "$dir/r.json" "$label" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
q = d["quality"]
print(f"{sys.argv[2]:<12} {d['vertices']:>9} {d['triangles']:>9} {d['seconds']:>10.2f} {d['vertices_per_second']:>12.0f} "
      f"{q['smallest_angle_degrees']['min']:>9.2f} {q['smallest_angle_degrees']['p5']:>9.2f} "
      f"{q['radius_edge']['max']:>9.3f} {q['distortion']['max']:>10.3f}"
      + ("" if d["converged"] and d["valid_triangulation"] else f"   [{d['status']}; {d['validation']}]"))
PY
done
printf '%-12s %9s %9s %10s %12s %9s %9s %9s %10s\n' "mmg2d*" "~81000" "-" "~6" "~13500" \
  "~15" "-" "-" "-"
echo "* mmg2d: the anchor the issue gives for this machine kind (about 81k vertices in about 6 s, worst smallest angle about 15° in the metric, no guarantee); not run here."
echo
echo "Voronoi refiner: diagram updated across rounds vs rebuilt every round (CPU s of the process)"
printf '%-26s %9s %9s %7s %10s %10s %8s  %s\n' run vertices triangles rounds updated rebuilt speedup mesh
domains=scenarios/domains
vruns=("square|$field" "$domains/square-with-holes.txt|thesis" "$domains/l-shape-with-wall.txt|thesis"
       "$domains/l-shape-with-wall.txt|shock")
[ "${1:-}" = "--quick" ] && vruns=("${vruns[@]:0:2}")
for run in "${vruns[@]}"; do
  IFS='|' read -r domain metric <<<"$run"
  label="$(basename "$domain" .txt),${metric%%:*}"
  cpu=()
  for mode in updated rebuilt; do
    flag=$([ $mode = rebuilt ] && echo --rebuild-diagram || true)
    /usr/bin/time -f "%U %S" -o "$dir/$mode.time" "$laguerre" mesh "$domain" --algorithm voronoi --metric "$metric" \
      -o "$dir/v-$mode" --force --no-picture --json $flag > "$dir/v-$mode.json" || true
    cpu+=("$(awk '{printf "%.2f", $1 + $2}' "$dir/$mode.time")")
  done
  same=$(cmp -s "$dir/v-updated.mesh" "$dir/v-rebuilt.mesh" && echo identical || echo DIFFERENT)
  python3 - "$dir/v-updated.json" "$label" "${cpu[0]}" "${cpu[1]}" "$same" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); u, r = float(sys.argv[3]), float(sys.argv[4])
print(f"{sys.argv[2]:<26} {d['vertices']:>9} {d['triangles']:>9} {d['rules']['rounds']:>7} {u:>10.2f} {r:>10.2f} "
      f"{r / max(u, 1e-9):>7.1f}x  {sys.argv[5]}" + ("" if d["converged"] else f"   [{d['status']}]"))
PY
done
