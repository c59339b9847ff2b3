#!/usr/bin/env bash
# Times the README's two commands the way a fresh machine runs them: a fresh clone of HEAD in a
# scratch folder, an empty compiler cache (CCACHE_DIR inside the scratch folder), then
#   1. tools/run-example.sh  (packages, Release build of the program, the quick-start scenario),
#   2. tools/test.sh         (Release build of the rest and its tests, sanitizer build and tests),
#   3. tools/test.sh again after touching one core .cpp (the incremental loop of a developer).
# Prints each step's own timing lines (bootstrap/test.sh report configure, build and test seconds)
# and the wall time of each command, with the machine's load before and after.
#   tools/bench/build-time.sh [--keep] [--touch core/src/…/File.cpp]
# Packages already installed are not reinstalled, so on a machine that has them the package step is
# not part of the figures (bootstrap prints its time when it does install).
set -euo pipefail
src="$(cd "$(dirname "$0")/../.." && pwd)"
keep=0
touch_file=core/src/packing/Thurston.cpp
while [ $# -gt 0 ]; do
  case "$1" in
    --keep) keep=1; shift ;;
    --touch) touch_file="$2"; shift 2 ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    *) echo "build-time: unknown argument '$1' (expected --keep or --touch FILE)" >&2; exit 2 ;;
  esac
done
work="$(mktemp -d /tmp/laguerre-fresh.XXXXXX)"
[ "$keep" -eq 1 ] || trap 'rm -rf "$work"' EXIT
git clone -q "$src" "$work/laguerre"
export CCACHE_DIR="$work/ccache"
cd "$work/laguerre"
echo "fresh clone of $(git rev-parse --short HEAD) in $work; load before: $(cut -d' ' -f1-3 /proc/loadavg)"

step=0
timed() {  # timed LABEL COMMAND…: runs it, keeps its timing lines, prints the wall time
  local label="$1"; shift
  local log="$work/step-$((++step)).log"
  local started=$SECONDS
  "$@" > "$log" 2>&1 || { echo "$label failed; log: $log" >&2; tail -30 "$log" >&2; exit 1; }
  grep -E '^(bootstrap|test\.sh):' "$log" | sed 's/^/  /'
  printf '%-34s %5d s  (load %s)\n' "$label" "$((SECONDS - started))" "$(cut -d' ' -f1-3 /proc/loadavg)"
}
timed "tools/run-example.sh" tools/run-example.sh
timed "tools/test.sh" tools/test.sh
touch "$touch_file"
timed "tools/test.sh (touched $(basename "$touch_file"))" tools/test.sh
if [ "$keep" -eq 1 ]; then echo "kept $work"; fi
