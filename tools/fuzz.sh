#!/usr/bin/env bash
# Fuzzing campaign: builds the libFuzzer harnesses of tests/fuzz (CMake preset `fuzz`: clang-14,
# -fsanitize=fuzzer,address,undefined) and runs each on a scratch copy of its seed corpus (the
# repository's corpus is never written), then prints one row per harness: executions, executions per
# second, coverage (libFuzzer's cov and ft counters), crashes (with the saved reproducers).
#
#   tools/fuzz.sh [--executions N] [--seconds S] [--jobs J] [--max-len L] [--no-build] [HARNESS...]
#
# HARNESS is a name of tests/fuzz/corpus (edges, coords, planar_code, graphml, dot, scenario, sites,
# domain, metric, codec); all of them by default. --executions is libFuzzer's -runs per harness
# (default 1000000), --seconds a time cap per harness (-max_total_time, default none), --jobs how many
# harnesses run at once (default 1). Work files and reproducers go to build/fuzz/campaign/<harness>/.
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
executions=1000000 seconds=0 jobs=1 max_len=4096 build=1
harnesses=()
while [ $# -gt 0 ]; do
  case "$1" in
    --executions) executions=$2; shift 2 ;;
    --seconds) seconds=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --max-len) max_len=$2; shift 2 ;;
    --no-build) build=0; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 2 ;;
    *) harnesses+=("$1"); shift ;;
  esac
done
if [ ${#harnesses[@]} -eq 0 ]; then
  harnesses=(edges coords planar_code graphml dot scenario sites domain metric codec)
fi
for h in "${harnesses[@]}"; do
  [ -d "$root/tests/fuzz/corpus/$h" ] || { echo "fuzz.sh: no harness '$h' (no tests/fuzz/corpus/$h)" >&2; exit 2; }
done

bin="$root/build/fuzz/tests/fuzz"
if [ $build -eq 1 ]; then
  (cd "$root" && cmake --preset fuzz >/dev/null)
  targets=()
  for h in "${harnesses[@]}"; do targets+=("${h}_fuzz"); done
  nice cmake --build "$root/build/fuzz" --target "${targets[@]}" -j"$jobs"
fi

campaign="$root/build/fuzz/campaign"
run_one() {  # harness
  local h=$1 dir="$campaign/$1"
  rm -rf "$dir" && mkdir -p "$dir/corpus" "$dir/artifacts"
  cp "$root/tests/fuzz/corpus/$h/"* "$dir/corpus/"
  local seeds=("$dir/corpus")
  if [ -d "$root/tests/fuzz/regressions/$h" ]; then seeds+=("$root/tests/fuzz/regressions/$h"); fi
  local limits=(-runs="$executions" -max_len="$max_len" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1)
  if [ "$seconds" != 0 ]; then limits+=(-max_total_time="$seconds"); fi
  # libFuzzer stops at the first crash (saved under artifacts/); new inputs go to the scratch corpus.
  (cd "$dir" && "$bin/${h}_fuzz" "${limits[@]}" -artifact_prefix="$dir/artifacts/" "${seeds[@]}" \
     > "$dir/log.txt" 2>&1) || true
}

for h in "${harnesses[@]}"; do
  run_one "$h" &
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do sleep 1; done
done
wait

printf '%-12s %12s %9s %8s %8s %8s  %s\n' harness executions exec/s cov ft crashes reproducers
for h in "${harnesses[@]}"; do
  dir="$campaign/$h" log="$campaign/$h/log.txt"
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | awk '{print $2}')
  speed=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | awk '{print $2}')
  last=$(grep -E '^#[0-9]+' "$log" | tail -1)  # "#N DONE cov: C ft: F corp: ..."
  cov=$(echo "$last" | grep -o 'cov: [0-9]*' | awk '{print $2}')
  ft=$(echo "$last" | grep -o 'ft: [0-9]*' | awk '{print $2}')
  crashes=$(find "$dir/artifacts" -type f | wc -l)
  printf '%-12s %12s %9s %8s %8s %8s  %s\n' "$h" "${execs:-0}" "${speed:--}" "${cov:--}" "${ft:--}" "$crashes" \
    "$(find "$dir/artifacts" -type f | head -3 | tr '\n' ' ')"
done
