#!/usr/bin/env bash
# GOPack (Collins–Orick–Stephenson, MATLAB, run under GNU Octave) and laguerre side by side, in one run,
# on the same complexes: GOPack's bundled complexes and uniform random triangulations / 3-connected maps.
#
#   tools/bench/gopack.sh [--gopack DIR] [--install] [--gopack-timeout S] [--laguerre-timeout S]
#                         [--complexes "Pinwheel_K mixed10000_K ..."] [--random "tri:1000 tri:10000 3c:1000 ..."]
#                         [--seed S] [--max-passes P] [--stall-passes K] [--out DIR] [--laguerre BIN]
#
#   --gopack DIR          the GOPack anchor (code/, complexes/*.p, edges/*.edges); default ../shared/anchors/gopack
#                         next to the checkout, i.e. /work/shared/anchors/gopack
#   --install             install Debian's octave (apt-get) if it is missing; without it a missing octave is an error
#   --gopack-timeout S    GOPack's wall-time bound per input (default 600): no pass starts after S seconds, and the
#                         process is killed at 2 S; such a run is reported as "timeout"
#   --laguerre-timeout S  the same bound per laguerre run (default 600)
#   --max-passes P        cap on GOPack's passes (default 100000); reaching it is reported as "stall"
#   --stall-passes K      a GOPack run whose best visual error has not improved for K passes (default 25) stops, "stall"
#   --laguerre BIN        the laguerre executable (default: build/release/tools/laguerre, built if missing)
#   --out DIR             where the inputs, logs and JSON of every run go (default: a fresh /tmp/gopack-bench.*)
#   --complexes LIST      which of the anchor's complexes (default: all four)
#   --random LIST         random inputs, kind:n with kind tri (uniform random triangulation, punctured at its vertex of
#                         largest degree: `laguerre generate uniform-triangulation`) or 3c (uniform random 3-connected
#                         map, largest face outside: `laguerre generate uniform-three-connected`); default
#                         "tri:1000 tri:10000 3c:1000 3c:10000"
#
# Per input, GOPack gets the complex as a CirclePack .p file and laguerre the same complex as an edge list with its
# boundary (`# outer:`): the anchor's files for its complexes, and for random inputs both files written from one
# embedding (vertices renumbered 1..n). GOPack packs triangulations only, with tangencies: a 3-connected map is given to
# both as its star triangulation (a new vertex in every inner face that is not a triangle, joined to its corners);
# laguerre's own packing of the map (face circles orthogonal, GLPD) is reported on a separate row.
#
# Runs: GOPack maximal packing, one riffle pass at a time, until its rule (max visual error
# | |c_v − c_w| − (r_v + r_w) | / r_v over interior v and petals w ≤ 1%) or the time bound; laguerre `pack` to
# LPD/GLPD and to `--stop exact` (every edge's tangency error ≤ 1% of the smaller radius: at least as strict as
# GOPack's rule), each with --accelerate newton and plain. Every run's final circles are checked by this script with
# GOPack's visual error, NaN radii/centres counted: GOPack's "visErr 0" on NaN radii is reported as "NaN", not success.
# Columns: passes (GOPack riffle passes, laguerre Newton steps or Jacobi sweeps), compute seconds (riffles / pack),
# wall and CPU seconds and peak RSS of the whole process (/usr/bin/time), final errors, and GOPack ÷ laguerre ratios
# of CPU seconds.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
gopack="$root/../shared/anchors/gopack"
[[ -d $gopack ]] || gopack=/work/shared/anchors/gopack
laguerre="$root/build/release/tools/laguerre"
install=0 gtimeout=600 ltimeout=600 seed=1 maxpasses=100000 stallpasses=25 out=""
complexes="Pinwheel_K mixed10000_K lace42000_K twist41000_K"
random="tri:1000 tri:10000 3c:1000 3c:10000"
while (($#)); do
  case "$1" in
    --gopack) gopack=$2; shift ;;
    --install) install=1 ;;
    --gopack-timeout) gtimeout=$2; shift ;;
    --laguerre-timeout) ltimeout=$2; shift ;;
    --complexes) complexes=$2; shift ;;
    --random) random=$2; shift ;;
    --seed) seed=$2; shift ;;
    --max-passes) maxpasses=$2; shift ;;
    --stall-passes) stallpasses=$2; shift ;;
    --out) out=$2; shift ;;
    --laguerre) laguerre=$2; shift ;;
    -h|--help) sed -n '2,38p' "$0"; exit 0 ;;
    *) echo "gopack.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
for v in "$gtimeout" "$ltimeout" "$seed" "$maxpasses" "$stallpasses"; do
  [[ $v =~ ^[0-9]+$ ]] || { echo "gopack.sh: expected a whole number, found '$v'" >&2; exit 2; }
done
[[ -d $gopack/code/@GOPacker ]] || { echo "gopack.sh: $gopack/code/@GOPacker not found (--gopack DIR)" >&2; exit 2; }
if ! command -v octave >/dev/null; then
  if ((install)); then
    echo "installing octave (Debian package)..." >&2
    if [[ $(id -u) == 0 ]]; then apt-get install -y octave >&2; else sudo apt-get install -y octave >&2; fi
  else
    echo "gopack.sh: octave is not installed; pass --install to install Debian's octave" >&2; exit 2
  fi
fi
[[ -x /usr/bin/time ]] || { echo "gopack.sh: /usr/bin/time (Debian package time) is needed for peak memory" >&2; exit 2; }

if [[ ! -x $laguerre ]]; then
  cmake --preset release -S "$root" >/dev/null && cmake --build --preset release --target laguerre >/dev/null
fi
work=${out:-$(mktemp -d /tmp/gopack-bench.XXXXXX)}
mkdir -p "$work"
py="$work/gopack_bench.py"
cat >"$py" <<'PY'
import json, math, sys

def load(path):
    with open(path) as f:
        return json.load(f)

def visual_error(doc):
    """GOPack's rule on an embedding JSON: max over interior v and neighbours w of ||c_v-c_w|-(r_v+r_w)|/r_v,
    and the number of vertices with a non-finite x, y or r."""
    by_id = {v["id"]: v for v in doc["vertices"]}
    bad = sum(1 for v in doc["vertices"] if not all(math.isfinite(v[k]) for k in ("x", "y", "r")))
    worst = 0.0
    for v in doc["vertices"]:
        if v["boundary"]:
            continue
        for w in (by_id[i] for i in v["neighbours"]):
            e = abs(math.hypot(v["x"] - w["x"], v["y"] - w["y"]) - (v["r"] + w["r"])) / v["r"]
            if math.isnan(e):
                bad = max(bad, 1)
            else:
                worst = max(worst, e)
    return worst, bad

def faces(rot):
    """Faces of a rotation system {v: [neighbours in order]}, as vertex lists."""
    pos = {v: {w: i for i, w in enumerate(nb)} for v, nb in rot.items()}
    seen, out = set(), []
    for u in rot:
        for v in rot[u]:
            if (u, v) in seen:
                continue
            face, a, b = [], u, v
            while (a, b) not in seen:
                seen.add((a, b))
                face.append(a)
                nb = rot[b]
                c = nb[(pos[b][a] - 1) % len(nb)]
                a, b = b, c
            out.append(face)
    return out

def convert(doc_path, p_path, edges_path, star):
    """The embedding's complex (star-triangulated if `star`), renumbered 1..n, as a CirclePack .p file and a
    laguerre edge list with its boundary."""
    doc = load(doc_path)
    rot = {v["id"]: list(v["neighbours"]) for v in doc["vertices"]}
    outer = list(doc["outer_face"])
    if star:
        outer_set = set(outer)
        nxt = max(rot) + 1
        for f in faces(rot):
            if len(f) == 3 or (len(f) == len(outer) and set(f) == outer_set):
                continue
            c = nxt
            nxt += 1
            rot[c] = list(f)
            k = len(f)
            for i, a in enumerate(f):
                z = f[(i - 1) % k]  # the face enters a from z and leaves to the petal just before z
                rot[a].insert(rot[a].index(z), c)
        # check: every inner face is now a triangle
        for f in faces(rot):
            assert len(f) == 3 or set(f) == outer_set, f
    ids = sorted(rot)
    num = {v: i + 1 for i, v in enumerate(ids)}
    bd_next = {outer[i]: outer[(i + 1) % len(outer)] for i in range(len(outer))}
    bd_prev = {b: a for a, b in bd_next.items()}
    # Open flowers: petals from one boundary neighbour to the other, around the side that is not the outer face.
    votes = [0, 0]
    def open_at(v, first):
        nb = rot[v]
        j = nb.index(first)
        return nb[j:] + nb[:j]
    for v in outer:
        if len(rot[v]) < 3:
            continue
        f = open_at(v, bd_next[v])
        votes[0 if f[-1] == bd_prev[v] else 1] += 1
    first_is_next = votes[0] >= votes[1]
    with open(p_path, "w") as f:
        f.write("NODECOUNT: %d\nGEOMETRY: euclidean\nFLOWERS:\n" % len(ids))
        for v in ids:
            if v in bd_next:
                pet = open_at(v, bd_next[v] if first_is_next else bd_prev[v])
            else:
                pet = rot[v] + rot[v][:1]
            f.write("%d %d  %s\n" % (num[v], len(pet) - 1, " ".join(str(num[w]) for w in pet)))
        f.write("END\n")
    edges = sorted({(min(num[a], num[b]), max(num[a], num[b])) for a in rot for b in rot[a]})
    with open(edges_path, "w") as f:
        f.write("# %s%s: %d vertices, %d edges\n" % (doc.get("name", ""), " (star triangulation)" if star else "",
                                                   len(ids), len(edges)))
        f.write("# outer: " + " ".join(str(num[v]) for v in outer) + "\n")
        for a, b in edges:
            f.write("%d %d\n" % (a, b))
    print(len(ids), len(outer))

def summary(doc_path, time_path):
    """One laguerre run: status iterations pack_seconds max_tangency visual_error nonfinite wall peak_mb cpu."""
    wall, peak, user, system = open(time_path).read().split()[-4:]
    cpu = "%.2f" % (float(user) + float(system))
    try:
        doc = load(doc_path)
    except Exception:
        print("killed(timeout) - - - - - %s %.0f %s" % (wall, int(peak) / 1024, cpu))
        return
    p = doc["packing"]
    ve, bad = visual_error(doc)
    print("%s %d %.3f %.3g %.3g %d %s %.0f %s" % (p["status"], p["iterations"], p["seconds"], p["max_tangency_error"],
                                                   ve, bad, wall, int(peak) / 1024, cpu))

if __name__ == "__main__":
    {"convert": lambda a: convert(a[0], a[1], a[2], a[3] == "1"), "summary": lambda a: summary(*a)}[sys.argv[1]](sys.argv[2:])
PY

# GOPack's driver: the anchor driver's loop (one continueRiffle(1) per pass, stop at max visual error ≤ 0.01), plus a
# NaN count of the final radii and centres.
gopack_run() {  # label p_file -> prints: passes riffle_seconds final_err nan_count stop_reason
  local label=$1 p=$2
  local m="$work/$label.m"
  cat >"$m" <<OCT
t0 = tic; gop = GOPacker(); gop.readpack('$p'); gop.setMode(1);
pass = 0; err = Inf; cum = 0; why = 'rule'; best = Inf; best_pass = 0;
while err > 0.01
  if pass >= $maxpasses || pass - best_pass >= $stallpasses, why = 'stall'; break; end
  if toc(t0) > $gtimeout, why = 'timeout'; break; end
  tp = tic; gop.continueRiffle(1); cum = cum + toc(tp); pass = pass + 1;
  err = gop.visErrMonitor(end);
  if err < best, best = err; best_pass = pass; end
  fprintf(stderr, '[$label] pass %d cum %.1fs maxVisErr %.4g\n', pass, cum, err);
end
nans = sum(isnan(gop.localradii(:))) + sum(isnan(real(gop.localcenters(:)))) + sum(isnan(imag(gop.localcenters(:))));
printf('GOPACK %d %.3f %.6g %d %s\n', pass, cum, err, nans, why);
OCT
  local log="$work/$label.gopack.log"
  (cd "$gopack/code" && /usr/bin/time -f "%e %M %U %S" -o "$work/$label.gopack.time" \
     timeout $((2 * gtimeout + 60)) octave --no-gui --norc -q --eval "source('$m')" >"$log" 2>"$log.err") || true
  local res
  res=$(grep -o 'GOPACK .*' "$log" | tail -1 | cut -d' ' -f2-)
  [[ -n $res ]] || res="$(grep -c 'pass ' "$log.err" || true) - - - killed"
  local t
  t=$(tail -1 "$work/$label.gopack.time" 2>/dev/null || echo '- 0 0 0')
  read -r w k u s <<<"$t"
  echo "$res $w $k $(python3 -c "print('%.1f' % ($u + $s))")"
}

laguerre_run() {  # label edges stop accel -> prints the summary line
  local label=$1 edges=$2 stop=$3 accel=$4
  local stem="$work/$label.$stop.$accel"
  /usr/bin/time -f "%e %M %U %S" -o "$stem.time" timeout "$ltimeout" "$laguerre" pack "$edges" --stop "$stop" \
    --accelerate "$accel" --max-iterations 100000000 --no-picture --json >"$stem.json" 2>"$stem.err" || true
  python3 "$py" summary "$stem.json" "$stem.time"
}

inputs=()  # label|p file|edges file|note
for c in $complexes; do
  [[ -f $gopack/complexes/$c.p && -f $gopack/edges/$c.edges ]] || { echo "gopack.sh: no complex $c in $gopack" >&2; exit 2; }
  inputs+=("$c|$gopack/complexes/$c.p|$gopack/edges/$c.edges|GOPack's complex")
done
maps=()  # label|edges of the 3-connected map itself
for r in $random; do
  kind=${r%%:*} n=${r#*:}
  case "$kind" in
    tri) family=uniform-triangulation star=0 ;;
    3c) family=uniform-three-connected star=1 ;;
    *) echo "gopack.sh: --random expects tri:N or 3c:N, found '$r'" >&2; exit 2 ;;
  esac
  label="$kind$n"
  "$laguerre" generate "$family" -n "$n" --seed "$seed" --format edges -o "$work/$label.orig.edges" --force 2>/dev/null
  "$laguerre" pack "$work/$label.orig.edges" --stop cap --max-iterations 1 --no-picture --json \
    >"$work/$label.orig.json" 2>/dev/null || true
  python3 "$py" convert "$work/$label.orig.json" "$work/$label.p" "$work/$label.edges" "$star" >/dev/null
  note="$family n=$n seed $seed"
  ((star)) && { note="$note, star triangulation"; maps+=("$label|$work/$label.orig.edges"); }
  inputs+=("$label|$work/$label.p|$work/$label.edges|$note")
done

echo "GOPack vs laguerre, one run, $(date -u +%FT%TZ); laguerre $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo "(no git)"); $(octave --version | head -1)"
echo "machine: $(nproc) cores; load before: $(uptime | sed 's/.*load average: //')"
echo "work files: $work"
printf '%-15s %7s %4s | %-30s | %-34s | %-34s | %-34s | %-34s | %9s %9s\n' input n bdry \
  "GOPack: passes s wall cpu MB err" "lag LPD newton: it s wall cpu MB err" "lag LPD plain: it s wall cpu MB err" \
  "lag exact newton: it s wall cpu MB err" "lag exact plain: it s wall cpu MB err" "x(newton)" "x(plain)"
fmt_l() {  # summary line -> "status it s wall MB [err]"
  local st it s tang ve bad wall mb cpu
  read -r st it s tang ve bad wall mb cpu <<<"$1"
  local tag=""
  [[ $st == converged ]] || tag="$st "
  ((bad > 0)) 2>/dev/null && tag="${tag}NaN "
  printf '%s%s %s %s %s %s %s' "$tag" "$it" "$s" "$wall" "$cpu" "$mb" "$ve"
}
for entry in "${inputs[@]}"; do
  IFS='|' read -r label p edges note <<<"$entry"
  n=$(grep -c '^[0-9]' "$p" || true)
  bdry=$(grep -m1 '^# outer:' "$edges" | wc -w); bdry=$((bdry - 2))
  read -r g_pass g_sec g_err g_nan g_why g_wall g_kb g_cpu <<<"$(gopack_run "$label" "$p")"
  if [[ $g_why == killed ]]; then g_stat="killed(timeout)";
  elif [[ $g_nan != 0 && $g_nan != - ]]; then g_stat="NaN($g_nan, reports $g_err)";
  elif [[ $g_why == rule ]]; then g_stat="ok";
  else g_stat="$g_why"; fi
  ln=$(laguerre_run "$label" "$edges" lpd newton)
  lp=$(laguerre_run "$label" "$edges" lpd plain)
  en=$(laguerre_run "$label" "$edges" exact newton)
  ep=$(laguerre_run "$label" "$edges" exact plain)
  ratio() {  # GOPack CPU seconds / laguerre CPU seconds (whole processes), when GOPack met its rule
    local cpu st
    st=$(cut -d' ' -f1 <<<"$1"); cpu=$(cut -d' ' -f9 <<<"$1")
    if [[ $g_stat == ok && $st == converged ]]; then python3 -c "print('%.0f' % ($g_cpu / max($cpu, 0.01)))";
    elif [[ $st == converged ]]; then python3 -c "print('>%.0f' % ($g_cpu / max($cpu, 0.01)))"; else echo "-"; fi
  }
  printf '%-15s %7s %4s | %-30s | %-34s | %-34s | %-34s | %-34s | %9s %9s\n' "$label" "$n" "$bdry" \
    "$g_stat $g_pass $g_sec $g_wall $g_cpu $((g_kb / 1024)) $g_err" "$(fmt_l "$ln")" "$(fmt_l "$lp")" "$(fmt_l "$en")" \
    "$(fmt_l "$ep")" "$(ratio "$en")" "$(ratio "$ep")"
  echo "  ($note)"
done
for entry in "${maps[@]}"; do
  IFS='|' read -r label edges <<<"$entry"
  ln=$(laguerre_run "$label-map" "$edges" lpd newton)
  en=$(laguerre_run "$label-map" "$edges" exact newton)
  echo "$label map itself (laguerre GLPD packing, face circles orthogonal; GOPack has no such mode): LPD newton $(fmt_l "$ln"); exact newton $(fmt_l "$en")"
done
echo "load after: $(uptime | sed 's/.*load average: //')"
cat <<'EOF'
Columns: GOPack status (ok = max visual error <= 1%; timeout = no pass started after --gopack-timeout; stall = pass cap or
no better visual error for --stall-passes passes; NaN = non-finite radii or centres, whatever visErr it reports), passes, riffle seconds, process wall seconds, process
CPU seconds, peak MB, final max visual error. laguerre: status (blank = converged), iterations (Newton steps or Jacobi sweeps), pack seconds,
process wall seconds, process CPU seconds (user + system), peak MB, final max visual error (GOPack's rule, computed by
this script on laguerre's circles). x(newton), x(plain) = GOPack CPU seconds / laguerre `--stop exact` CPU seconds, whole
processes (CPU rather than wall: less sensitive to the machine's load); "> " when GOPack did not meet its rule.
EOF
