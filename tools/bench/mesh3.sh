#!/usr/bin/env bash
# The 3D star mesher (issue 16 §1) on every bundled 3D domain under every bundled 3D field, one run
# each: checked status, vertices, tetrahedra, CPU seconds of the process (user + sys, /usr/bin/time:
# the machine is shared, wall time is not the mesher's), smallest dihedral (min, p5), slivers, the
# inconsistent tetrahedra the last consistency sweep found, all but the time from `laguerre mesh
# --json` (quality in each vertex's metric), and the SHA-256 of the .mesh (first 12 hex digits).
#   tools/bench/mesh3.sh [--quick] [--known] [--against EXE]
#   --quick        uniform and shock only
#   --known        also the known cascading case: the former bench field sphere:0.15:0.4:0.5:0.3
#                  (docs/star-mesher3.md: it rotates by ~1 rad per element, outside the thesis's
#                  hypothesis; expected to stop at the cap)
#   --against EXE  run every row with EXE too (an older build of laguerre) and print its row under
#                  the current one, the CPU ratio EXE / current and whether the two .mesh files are
#                  byte-identical
# Fields: uniform, the plane shock, the curved sphere shock (sphere:0.2:0.4:0.5:2:0.5:0.5:-1.5: a
# sphere of radius 2 centred below the cube, whose layer crosses the cube as a curved sheet near
# z = 0.4–0.5; it replaced the former sphere field, see docs/star-mesher3.md), a muparser expression
# (size growing along z) and a background tetrahedral mesh (the cube meshed under the uniform field,
# with its .sol). Each run is capped at MESH3_MAX_VERTICES (4000) vertices and MESH3_TIMEOUT (300)
# seconds; a row that hits either says so.
set -euo pipefail
cd "$(dirname "$0")/../.."
quick=0 known=0 against=""
while (($#)); do
  case "$1" in
    --quick) quick=1 ;;
    --known) known=1 ;;
    --against) against=$(realpath "$2"); shift ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "mesh3.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
[[ -z $against || -x $against ]] || { echo "mesh3.sh: --against: '$against' is not an executable" >&2; exit 2; }
source tools/bench/common.sh
max=${MESH3_MAX_VERTICES:-4000}
limit=${MESH3_TIMEOUT:-300}
domains=(scenarios/domains/cube.off scenarios/domains/box-with-hole.off)
"$laguerre" mesh scenarios/domains/cube.off --metric uniform:0.2:0.2:0.2 -o "$dir/bg" --force --no-picture >/dev/null
# label|field|extra options
fields=("uniform|uniform:0.15:0.15:0.3|" "shock|shock:0.2:0.4:0.5:0.5|" "sphere|sphere:0.2:0.4:0.5:2:0.5:0.5:-1.5|"
        "expr|expr:xx=25;xy=0;xz=0;yy=25;yz=0;zz=25/(1+2*z)^2|" "mesh|mesh:$dir/bg.mesh:$dir/bg.sol|")
((quick)) && fields=("${fields[@]:0:2}")
((known)) && fields+=("sphere-known|sphere:0.15:0.4:0.5:0.3:0.5:0.5:0.5|--distortion 2.5")
echo "load: $(uptime | sed 's/.*load average/load average/'); $laguerre${against:+ against $against}"
printf '%-14s %-13s %-4s %-8s %8s %8s %8s %8s %8s %7s %7s %-12s\n' domain field exe status vertices tets cpu_s \
  min_dih p5_dih slivers last_inc mesh_sha256
# row EXE TAG DOMAIN LABEL FIELD EXTRA: one run, prints its row; sets `cpu` and `sha`.
row() {
  local exe=$1 tag=$2 domain=$3 label=$4 field=$5 extra=$6
  rm -f "$dir/m-$tag.mesh" "$dir/r-$tag.json"
  # shellcheck disable=SC2086
  /usr/bin/time -f "%U %S" -o "$dir/t-$tag" timeout "$limit" "$exe" mesh "$domain" --metric "$field" $extra \
    --max-vertices "$max" -o "$dir/m-$tag" --force --no-picture --json > "$dir/r-$tag.json" 2>/dev/null || true
  cpu=$(awk 'END { printf "%.2f", $1 + $2 }' "$dir/t-$tag")
  sha=$( [[ -s $dir/m-$tag.mesh ]] && sha256sum "$dir/m-$tag.mesh" | cut -c1-12 || echo -)
  python3 - "$dir/r-$tag.json" "$(basename "$domain" .off)" "$label" "$tag" "$limit" "$cpu" "$sha" <<'PY'
import json, sys
path, domain, field, tag, limit, cpu, sha = sys.argv[1:]
try:
    d = json.load(open(path))
except (OSError, ValueError):
    print(f"{domain:<14} {field:<13} {tag:<4} {'timeout':<8} (no result within {limit} s)")
    sys.exit()
q = d["quality"]
ok = d["converged"] and d["valid_tetrahedralization"]
status = "checked" if ok else ("cap" if "max_vertices" in d["status"] else "FAILED")
last = d["rules"].get("last_sweep_inconsistent", "-")
print(f"{domain:<14} {field:<13} {tag:<4} {status:<8} {d['vertices']:>8} {d['tetrahedra']:>8} {float(cpu):>8.2f} "
      f"{q['smallest_dihedral_degrees']['min']:>8.2f} {q['smallest_dihedral_degrees']['p5']:>8.2f} {q['slivers']:>7} "
      f"{last:>7} {sha:<12}" + ("" if ok else f"   [{d['status']}]"))
PY
}
for domain in "${domains[@]}"; do
  for entry in "${fields[@]}"; do
    IFS='|' read -r label field extra <<<"$entry"
    row "$laguerre" new "$domain" "$label" "$field" "$extra"
    if [[ -n $against ]]; then
      new_cpu=$cpu new_sha=$sha
      row "$against" old "$domain" "$label" "$field" "$extra"
      python3 -c "import sys; n, o = float(sys.argv[1]), float(sys.argv[2]); print(f'{\"\":<14} {\"\":<13} old/new CPU {o / n if n else float(\"nan\"):.2f}x, meshes ' + ('byte-identical' if sys.argv[3] == sys.argv[4] and sys.argv[3] != '-' else 'DIFFER'))" \
        "$new_cpu" "$cpu" "$new_sha" "$sha"
    fi
  done
done
echo "load after: $(uptime | sed 's/.*load average/load average/')"
