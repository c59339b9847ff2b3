#!/usr/bin/env bash
# The 3D star mesher (issue 16 §1) on every bundled 3D domain under every bundled 3D field, one run
# each: checked status, vertices, tetrahedra, wall seconds, smallest dihedral (min, p5) and slivers, all
# from `laguerre mesh --json` (quality in each vertex's metric).
#   tools/bench/mesh3.sh [--quick]    (--quick: uniform and shock only)
# Fields: uniform, the plane shock, the sphere shock (with --distortion 2.5, as in the README), a
# muparser expression (size growing along z) and a background tetrahedral mesh (the cube meshed under
# the uniform field, with its .sol). Each run is capped at MESH3_MAX_VERTICES (4000) vertices and
# MESH3_TIMEOUT (300) seconds; a row that hits either says so.
set -euo pipefail
cd "$(dirname "$0")/../.."
source tools/bench/common.sh
max=${MESH3_MAX_VERTICES:-4000}
limit=${MESH3_TIMEOUT:-300}
domains=(scenarios/domains/cube.off scenarios/domains/box-with-hole.off)
"$laguerre" mesh scenarios/domains/cube.off --metric uniform:0.2:0.2:0.2 -o "$dir/bg" --force --no-picture >/dev/null
fields=("uniform:0.15:0.15:0.3" "shock:0.2:0.4:0.5:0.5" "sphere:0.15:0.4:0.5:0.3:0.5:0.5:0.5|--distortion 2.5"
        "expr:xx=25;xy=0;xz=0;yy=25;yz=0;zz=25/(1+2*z)^2" "mesh:$dir/bg.mesh:$dir/bg.sol")
[ "${1:-}" = "--quick" ] && fields=("${fields[@]:0:2}")
echo "load: $(uptime | sed 's/.*load average/load average/')"
printf '%-14s %-22s %-9s %8s %8s %8s %8s %8s %7s\n' domain field status vertices tets seconds min_dih p5_dih slivers
for domain in "${domains[@]}"; do
  for entry in "${fields[@]}"; do
    IFS='|' read -r field extra <<<"$entry"
    # shellcheck disable=SC2086
    timeout "$limit" "$laguerre" mesh "$domain" --metric "$field" $extra --max-vertices "$max" -o "$dir/m" --force \
      --no-picture --json > "$dir/r.json" 2>/dev/null || true
    python3 - "$dir/r.json" "$(basename "$domain" .off)" "${field%%:*}" "$limit" <<'PY'
import json, sys
path, domain, field, limit = sys.argv[1:]
try:
    d = json.load(open(path))
except (OSError, ValueError):
    print(f"{domain:<14} {field:<22} {'timeout':<9} (no result within {limit} s)")
    sys.exit()
q = d["quality"]
ok = d["converged"] and d["valid_tetrahedralization"]
status = "checked" if ok else ("cap" if "max_vertices" in d["status"] else "FAILED")
print(f"{domain:<14} {field:<22} {status:<9} {d['vertices']:>8} {d['tetrahedra']:>8} {d['seconds']:>8.1f} "
      f"{q['smallest_dihedral_degrees']['min']:>8.2f} {q['smallest_dihedral_degrees']['p5']:>8.2f} {q['slivers']:>7}"
      + ("" if ok else f"   [{d['status']}]"))
PY
  done
done
