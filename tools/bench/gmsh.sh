#!/usr/bin/env bash
# laguerre (stars, Voronoi) and gmsh's BAMG side by side, in one run, on the same 2D domains under the
# same metric fields (issue 16 §3). Every mesh, gmsh's included, is measured by laguerre's own report in
# the prescribed metric (`laguerre mesh-quality`, the report `laguerre mesh` prints).
#
#   tools/bench/gmsh.sh [--install] [--quick] [--2d|--3d] [--timeout S] [--gmsh-edge F] [--out DIR]
#
#   --install      install Debian's gmsh (apt-get) if it is missing; without it a missing gmsh is an error
#   --quick        the three small rows only (no 10^5-element row)
#   --timeout S    wall-time bound per run (default 900); a run stopped by it is reported as "timeout"
#   --gmsh-edge F  gmsh's target edge length in laguerre's metric, in units of the size bound S (default
#                  1.732 = sqrt 3: the edge of the equilateral triangle of circumradius S, the largest that
#                  `--size-bound S` allows)
#   --out DIR      keep the inputs, meshes, logs and JSON there (default: a scratch folder, removed)
#   --2d, --3d     only the 2D rows (triangles) or only the 3D rows (tetrahedra); default both
#
# Per row (domain, field, size bound S): `laguerre mesh --algorithm stars` and `--algorithm voronoi` with
# `--size-bound S` (Voronoi only on the small rows: its rounds are O(n) each), then gmsh 2D with
# `Mesh.Algorithm = 7` (BAMG) and a background tensor view: the stars mesh with the field's metric at each
# vertex (its .mesh + .sol) written as `TT` triangles of metric M/(F·S)² (gmsh's BAMG aims at unit edges
# in the tensor it is given, M = I/h² meaning size h, as laguerre's fields), so gmsh sees the field
# interpolated linearly on that mesh; the domain becomes a .geo (the polygon and holes as lines of one
# plane surface, constraint segments embedded with `Line{…} In Surface{1}`). gmsh writes Medit .mesh
# (Dimension 3, z = 0), which `laguerre mesh-quality --metric FIELD --domain DOMAIN` measures with the
# exact field at gmsh's vertices and checks as a triangulation of the domain.
# Columns: vertices, triangles, wall and CPU seconds of the whole process (/usr/bin/time: gmsh's include
# reading the background view), worst and 5th-percentile smallest angle in the metric, worst
# radius-edge ratio, edge lengths in the metric (min/max), and the status (converged/valid).
#
# 3D rows (tetrahedra): the domains and fields of tools/bench/mesh3.sh (cube.off and box-with-hole.off
# under uniform, plane shock, the curved sphere shock sphere:0.2:0.4:0.5:2:0.5:0.5:-1.5 (the former
# sphere:0.15:0.4:0.5:0.3 with --distortion 2.5 rotates by ~1 rad per element and cascades, see
# docs/star-mesher3.md; `mesh3.sh --known` runs it), muparser expression), laguerre's
# stars capped at MESH3_MAX_VERTICES (2000) vertices, then gmsh 3D; without --quick also a row of
# about 10^5 tetrahedra (cube, uniform:0.028:0.028:0.056, uncapped: the issue's size). Debian's gmsh 4.8.4 has no
# anisotropic 3D algorithm (BAMG is 2D; it is built without Mmg), so gmsh meshes isotropic tetrahedra
# (`Mesh.Algorithm3D = 1`, Delaunay) under a background scalar view: on the stars mesh of the row, the
# size F3·S/√λ_max(M) at each vertex (the field's smallest size, so that no edge is long in the metric;
# F3 = 4/√6 ≈ 1.633, the edge of the regular tetrahedron of circumradius S = 1). The .geo has the
# surface's coplanar triangles merged into plane surfaces (holes as inner curve loops), one surface
# loop and one volume. gmsh's mesh is measured by `laguerre mesh-quality MESH --metric FIELD --domain
# DOMAIN.off` (its boundary = the facets in one tetrahedron, checked as a tetrahedralization of the
# domain). Columns: vertices, tetrahedra, wall and CPU s, min and p5 dihedral angle in the metric,
# worst radius-edge, slivers (sliverity < 0.02 in a vertex's metric), edge lengths in the metric.
set -euo pipefail
cd "$(dirname "$0")/../.."
install=0 quick=0 timeout_s=900 edge=1.732 out="" two=1 three=1
while (($#)); do
  case "$1" in
    --install) install=1 ;;
    --quick) quick=1 ;;
    --timeout) timeout_s=$2; shift ;;
    --gmsh-edge) edge=$2; shift ;;
    --out) out=$2; shift ;;
    --2d) three=0 ;;
    --3d) two=0 ;;
    -h|--help) sed -n '2,43p' "$0"; exit 0 ;;
    *) echo "gmsh.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
if ! command -v gmsh >/dev/null; then
  if ((install)); then
    apt-get install -y --no-install-recommends gmsh >/dev/null
  else
    echo "gmsh.sh: gmsh is not installed (run with --install, or apt-get install gmsh)" >&2
    exit 2
  fi
fi
source tools/bench/common.sh
if [[ -n $out ]]; then  # keep the files there instead of common.sh's scratch folder
  rm -rf "$dir"
  trap - EXIT
  mkdir -p "$out"
  dir=$(cd "$out" && pwd)
fi
domains=scenarios/domains
shock="shock:0.002:0.05:0.03:0.5"
thick="shock:0.02:0.2:0.1:0.5"
# domain|field|size bound|algorithms
runs=("square|$thick|1|stars voronoi gmsh"
      "$domains/l-shape-with-wall.txt|thesis|1|stars voronoi gmsh"
      "$domains/square-with-holes.txt|thesis:0.15:4:0.2:0.5|1|stars voronoi gmsh")
((quick)) || runs+=("square|$shock|0.08|stars gmsh")
echo "gmsh $(gmsh --version 2>&1 | tail -1), laguerre $("$laguerre" --version | awk '{print $2}'); $(nproc) cores, load: $(uptime | sed 's/.*load average: //')"
# run_row WIDTH LABEL TOOL STEM DOMAIN FIELD COMMAND...: runs COMMAND under /usr/bin/time and the
# timeout, sets `wall` and `cpu`, and leaves the JSON report in STEM.json (gmsh's mesh measured by
# `laguerre mesh-quality`); prints the row itself and returns 1 when there is no report (timeout, or no
# mesh from gmsh).
run_row() {
  local width=$1 label=$2 tool=$3 stem=$4 domain=$5 field=$6 status=0
  shift 6
  /usr/bin/time -f "%e %U %S" -o "$stem.time" timeout "$timeout_s" "$@" > "$stem.out" 2> "$stem.err" || status=$?
  read -r wall user sys < <(tail -1 "$stem.time" | grep -E '^[0-9.]+ [0-9.]+ [0-9.]+$' || echo "- 0 0")
  cpu=$(python3 -c "print(f'{$user + $sys:.2f}')")
  if ((status == 124)); then
    printf "%-${width}s %-8s %8s %9s %8s %8s  %s\n" "$label" "$tool" - - "$wall" "$cpu" "timeout (${timeout_s} s)"
    return 1
  fi
  if [[ $tool == gmsh ]]; then
    if [[ ! -s $stem.mesh ]]; then
      printf "%-${width}s %-8s %8s %9s %8s %8s  %s\n" "$label" "$tool" - - "$wall" "$cpu" \
        "failed ($status): $(grep -m1 Error "$stem.out" "$stem.err" || true)"
      return 1
    fi
    "$laguerre" mesh-quality "$stem.mesh" --metric "$field" --domain "$domain" --json > "$stem.json" || true
  else
    cp "$stem.out" "$stem.json"
  fi
}
((two)) || runs=()
((two)) && printf '%-30s %-8s %8s %9s %8s %8s %8s %8s %8s %8s %8s  %s\n' row tool vertices triangles wall_s cpu_s \
  min_ang p5_ang max_rho min_len max_len status
for run in "${runs[@]}"; do
  IFS='|' read -r domain field bound tools <<<"$run"
  name=$(basename "$domain" .txt)
  label="$name,${field%%:*},S=$bound"
  base="$dir/$name-${field%%:*}-$bound"
  for tool in $tools; do
    stem="$base-$tool"
    if [[ $tool == gmsh ]]; then
      # The background view (from the stars mesh of this row) and the .geo of the domain.
      python3 - "$domain" "$base-stars.mesh" "$base-stars.sol" "$bound" "$edge" "$stem" <<'PY'
import sys
sys.path.insert(0, 'tools/bench')
from medit import medit
domain, mesh, sol, bound, edge, stem = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5]), sys.argv[6]
g = medit(mesh); m = medit(sol)['m']; s = 1 / (edge * bound) ** 2
with open(stem + '.pos', 'w') as f:
    f.write('View "metric" {\n')
    for a, b, c in g['t']:
        xs = ','.join('%.17g,%.17g,0' % g['v'][i] for i in (a, b, c))
        ms = ','.join('%.17g,%.17g,0,%.17g,%.17g,0,0,0,1' % (s * m[i][0], s * m[i][1], s * m[i][1], s * m[i][2]) for i in (a, b, c))
        f.write('TT(%s){%s};\n' % (xs, ms))
    f.write('};\n')
# The domain: outer polygon, holes, constraint segments (core/meshing/Domain.hpp).
loops, segments = [], []
if domain == 'square':
    loops = [[(0, 0), (1, 0), (1, 1), (0, 1)]]
else:
    for line in open(domain):
        w = line.split('#')[0].split()
        if not w: continue
        if w[0] in ('outer', 'hole'): loops.append([])
        elif w[0] == 'segment': segments.append(((float(w[1]), float(w[2])), (float(w[3]), float(w[4]))))
        else: loops[-1].append((float(w[0]), float(w[1])))
points, geo = {}, []
def point(p):
    if p not in points:
        points[p] = len(points) + 1
        geo.append('Point(%d) = {%.17g, %.17g, 0};' % (points[p], p[0], p[1]))
    return points[p]
lines = 0
# A constraint endpoint on another constraint (a wall ending on the boundary) splits it there, as
# Domain::constraint_pieces does for laguerre.
ends = {p for loop in loops for p in loop} | {p for seg in segments for p in seg}
def pieces(p, q):
    inner = [r for r in ends if r not in (p, q) and (q[0] - p[0]) * (r[1] - p[1]) == (q[1] - p[1]) * (r[0] - p[0])
             and min(p[0], q[0]) <= r[0] <= max(p[0], q[0]) and min(p[1], q[1]) <= r[1] <= max(p[1], q[1])]
    inner.sort(key=lambda r: abs(r[0] - p[0]) + abs(r[1] - p[1]))
    chain = [p] + inner + [q]
    return list(zip(chain, chain[1:]))
def line(p, q):
    global lines
    ids = []
    for a, b in pieces(p, q):
        lines += 1
        geo.append('Line(%d) = {%d, %d};' % (lines, point(a), point(b)))
        ids.append(lines)
    return ids
curve_loops = []
for k, loop in enumerate(loops):
    ids = [i for j in range(len(loop)) for i in line(loop[j], loop[(j + 1) % len(loop)])]
    geo.append('Curve Loop(%d) = {%s};' % (k + 1, ', '.join(map(str, ids))))
    curve_loops.append(k + 1)
geo.append('Plane Surface(1) = {%s};' % ', '.join(map(str, curve_loops)))
embedded = [i for p, q in segments for i in line(p, q)]
if embedded: geo.append('Line{%s} In Surface{1};' % ', '.join(map(str, embedded)))
geo += ['Merge "%s.pos";' % stem, 'Background Mesh View[0];', 'Mesh.Algorithm = 7;', 'Mesh.AnisoMax = 1e6;',
        'Mesh.MeshSizeExtendFromBoundary = 0;', 'Mesh.MeshSizeFromPoints = 0;', 'Mesh.MeshSizeFromCurvature = 0;']
open(stem + '.geo', 'w').write('\n'.join(geo) + '\n')
PY
      cmd=(gmsh "$stem.geo" -2 -format mesh -o "$stem.mesh")
    else
      cmd=("$laguerre" mesh "$domain" --algorithm "$tool" --metric "$field" --size-bound "$bound" -o "$stem"
           --force --no-picture --json)
    fi
    run_row 30 "$label" "$tool" "$stem" "$domain" "$field" "${cmd[@]}" || continue
    python3 - "$stem.json" "$label" "$tool" "$wall" "$cpu" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); q = d['quality']
state = ('converged, ' if d.get('converged') else ('' if 'converged' not in d else 'not converged, ')) + \
        ('valid' if d['valid_triangulation'] else 'INVALID: ' + d['validation'])
print(f"{sys.argv[2]:<30} {sys.argv[3]:<8} {d['vertices']:>8} {d['triangles']:>9} {sys.argv[4]:>8} {sys.argv[5]:>8} "
      f"{q['smallest_angle_degrees']['min']:>8.2f} {q['smallest_angle_degrees']['p5']:>8.2f} {q['radius_edge']['max']:>8.3f} "
      f"{q['edge_length']['min']:>8.3f} {q['edge_length']['max']:>8.3f}  {state}")
PY
  done
done

# --- 3D rows -------------------------------------------------------------------------------------
if ((three)); then
  max3=${MESH3_MAX_VERTICES:-2000}
  fields3=("uniform:0.15:0.15:0.3" "shock:0.2:0.4:0.5:0.5" "sphere:0.2:0.4:0.5:2:0.5:0.5:-1.5"
           "expr:xx=25;xy=0;xz=0;yy=25;yz=0;zz=25/(1+2*z)^2")
  printf '\n%-24s %-6s %8s %9s %8s %8s %8s %8s %8s %7s %8s %8s  %s\n' row tool vertices tetrahedra wall_s cpu_s \
    min_dih p5_dih max_rho slivers min_len max_len status
  # domain|field|row name; without --quick also the 10^5-tetrahedron row (the cube, uniform field fine
  # enough for ~1.0e5 stars tetrahedra, uncapped)
  rows3=()
  for domain in "$domains/cube.off" "$domains/box-with-hole.off"; do
    for field in "${fields3[@]}"; do rows3+=("$domain|$field|${field%%:*}"); done
  done
  ((quick)) || rows3+=("$domains/cube.off|uniform:0.028:0.028:0.056|uniform-1e5")
  for row3 in "${rows3[@]}"; do
    IFS='|' read -r domain field kind <<<"$row3"
    extra=""
    {
      name=$(basename "$domain" .off)
      label="$name,$kind"
      base="$dir/3d-$name-$kind"
      cap=$max3
      [[ $kind == uniform-1e5 ]] && cap=1000000
      for tool in stars gmsh; do
        stem="$base-$tool"
        if [[ $tool == gmsh ]]; then
          [[ -s $base-stars.mesh ]] || { printf '%-24s %-6s %s\n' "$label" gmsh "- (no stars mesh to carry the size field)"; continue; }
          python3 - "$domain" "$base-stars.mesh" "$base-stars.sol" "$stem" <<'PY'
import math, sys
sys.path.insert(0, 'tools/bench')
from medit import medit
domain, mesh, sol, stem = sys.argv[1:]
def largest_eigenvalue(m):  # symmetric 3x3 (xx, xy, yy, xz, yz, zz) in Medit's order
    a, b, d, c, e, f = m
    p1 = b * b + c * c + e * e
    q = (a + d + f) / 3
    p2 = (a - q) ** 2 + (d - q) ** 2 + (f - q) ** 2 + 2 * p1
    p = math.sqrt(p2 / 6)
    if p == 0: return a
    B = [[(a - q) / p, b / p, c / p], [b / p, (d - q) / p, e / p], [c / p, e / p, (f - q) / p]]
    det = (B[0][0] * (B[1][1] * B[2][2] - B[1][2] * B[2][1]) - B[0][1] * (B[1][0] * B[2][2] - B[1][2] * B[2][0])
           + B[0][2] * (B[1][0] * B[2][1] - B[1][1] * B[2][0]))
    phi = math.acos(max(-1, min(1, det / 2))) / 3
    return q + 2 * p * math.cos(phi)
g = medit(mesh); m = medit(sol)['m']
edge = 4 / math.sqrt(6)
h = [edge / math.sqrt(largest_eigenvalue(x)) for x in m]
with open(stem + '.pos', 'w') as out:
    out.write('View "size" {\n')
    for t in g['k']:
        xs = ','.join('%.17g,%.17g,%.17g' % g['v'][i] for i in t)
        out.write('SS(%s){%s};\n' % (xs, ','.join('%.17g' % h[i] for i in t)))
    out.write('};\n')
# The surface: OFF triangles grouped by plane (same outward normal, coplanar) and edge adjacency.
w = [l.split('#')[0].split() for l in open(domain)]
w = [x for x in w if x]
nv, nf = int(w[1][0]), int(w[1][1])
P = [tuple(float(c) for c in x[:3]) for x in w[2:2 + nv]]
T = [tuple(int(c) for c in x[1:4]) for x in w[2 + nv:2 + nv + nf]]
def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def dot(a, b): return sum(x * y for x, y in zip(a, b))
def normal(t):
    n = cross(sub(P[t[1]], P[t[0]]), sub(P[t[2]], P[t[0]])); l = math.sqrt(dot(n, n)); return tuple(x / l for x in n)
N = [normal(t) for t in T]
parent = list(range(nf))
def find(i):
    while parent[i] != i: parent[i] = parent[parent[i]]; i = parent[i]
    return i
by_edge = {}
for i, t in enumerate(T):
    for k in range(3): by_edge.setdefault(frozenset((t[k], t[(k + 1) % 3])), []).append(i)
for e, fs in by_edge.items():
    for j in fs[1:]:
        i = fs[0]
        if dot(N[i], N[j]) > 1 - 1e-12 and abs(dot(N[i], sub(P[T[j][0]], P[T[i][0]]))) < 1e-12: parent[find(j)] = find(i)
groups = {}
for i in range(nf): groups.setdefault(find(i), []).append(i)
geo = ['Point(%d) = {%.17g, %.17g, %.17g};' % (i + 1, *p) for i, p in enumerate(P)]
lines = {}
def line(a, b):
    key = (min(a, b), max(a, b))
    if key not in lines:
        lines[key] = len(lines) + 1
        geo.append('Line(%d) = {%d, %d};' % (lines[key], key[0] + 1, key[1] + 1))
    return lines[key] if a < b else -lines[key]
surfaces = []
loops = 0
for faces in groups.values():
    directed = {(T[i][k], T[i][(k + 1) % 3]) for i in faces for k in range(3)}
    border = {e for e in directed if (e[1], e[0]) not in directed}
    nxt = {a: b for a, b in border}
    rings = []
    while nxt:
        a = next(iter(nxt)); ring = [a]
        while nxt[ring[-1]] != a: ring.append(nxt.pop(ring[-1]))
        nxt.pop(ring[-1]); rings.append(ring)
    n = N[faces[0]]
    def area(r):  # signed, around the outward normal
        s = (0, 0, 0)
        for k in range(len(r)): s = tuple(x + y for x, y in zip(s, cross(P[r[k]], P[r[(k + 1) % len(r)]])))
        return dot(s, n) / 2
    rings.sort(key=lambda r: -abs(area(r)))
    ids = []
    for r in rings:
        loops += 1
        geo.append('Curve Loop(%d) = {%s};' % (loops, ', '.join(str(line(r[k], r[(k + 1) % len(r)])) for k in range(len(r)))))
        ids.append(loops)
    surfaces.append(len(surfaces) + 1)
    geo.append('Plane Surface(%d) = {%s};' % (surfaces[-1], ', '.join(map(str, ids))))
geo += ['Surface Loop(1) = {%s};' % ', '.join(map(str, surfaces)), 'Volume(1) = {1};',
        'Merge "%s.pos";' % stem, 'Background Mesh View[0];', 'Mesh.Algorithm3D = 1;',
        'Mesh.MeshSizeExtendFromBoundary = 0;', 'Mesh.MeshSizeFromPoints = 0;', 'Mesh.MeshSizeFromCurvature = 0;']
open(stem + '.geo', 'w').write('\n'.join(geo) + '\n')
PY
          cmd=(gmsh "$stem.geo" -3 -format mesh -o "$stem.mesh")
        else
          # shellcheck disable=SC2206
          cmd=("$laguerre" mesh "$domain" --metric "$field" $extra --max-vertices "$cap" -o "$stem" --force --no-picture --json)
        fi
        run_row 24 "$label" "$tool" "$stem" "$domain" "$field" "${cmd[@]}" || continue
        python3 - "$stem.json" "$label" "$tool" "$wall" "$cpu" <<'PY'
import json, sys
d = json.load(open(sys.argv[1])); q = d['quality']
if 'converged' in d:
    state = 'converged, ' if d['converged'] else ('cap, ' if 'max_vertices' in d['status'] else 'not converged, ')
else:
    state = ''
state += 'valid' if d['valid_tetrahedralization'] else 'INVALID: ' + d['validation']
print(f"{sys.argv[2]:<24} {sys.argv[3]:<6} {d['vertices']:>8} {d['tetrahedra']:>9} {sys.argv[4]:>8} {sys.argv[5]:>8} "
      f"{q['smallest_dihedral_degrees']['min']:>8.2f} {q['smallest_dihedral_degrees']['p5']:>8.2f} {q['radius_edge']['max']:>8.3f} "
      f"{q['slivers']:>7} {q['edge_length']['min']:>8.3f} {q['edge_length']['max']:>8.3f}  {state}")
PY
      done
    }
  done
fi
echo "load after: $(uptime | sed 's/.*load average: //')"
