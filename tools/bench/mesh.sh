#!/usr/bin/env bash
# Anisotropic meshing speed and quality on the shock-layer field in the unit square (issue 6), side by
# side with the anchor the issue gives for mmg2d (a metric-based remesher with no guarantee; not in
# Debian, so its row is the published figure for this machine kind, not a run).
#   tools/bench/mesh.sh [--quick]     (--quick: the three smaller sizes only)
# The field is the shock layer shock:0.002:0.05:0.03:0.5 (sizes 0.002 across the layer at x = 0.5,
# 0.05 elsewhere); --size-bound 1, 0.25, 0.08 and 0.05 give about 4.5·10^3, 8·10^3, 5·10^4 and 10^5
# vertices (the distortion bound γ₀ = 1.5 alone already forces a few thousand vertices into that
# layer), and a ten times thicker layer, shock:0.02:0.2:0.1:0.5, gives the 10^3 row. Quality is
# measured in the metric of every vertex of each triangle (the worst is kept).
set -euo pipefail
cd "$(dirname "$0")/../.."
tools/bootstrap.sh --preset release >/dev/null
laguerre=build/release/tools/laguerre
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
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
