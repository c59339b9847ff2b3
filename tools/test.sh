#!/usr/bin/env bash
# Sets everything up and runs the whole default test suite:
#   1. the Release build (warnings as errors) and every test except the `slow` label;
#   2. the -O1 build with AddressSanitizer + UndefinedBehaviorSanitizer (libraries and tests, no CLI)
#      and the `unit` tests (plus the `fuzz` smoke runs).
# Each step prints how long it took.
#   tools/test.sh [--no-sanitizers]
set -euo pipefail
cd "$(dirname "$0")/.."
sanitizers=1
[ "${1:-}" = "--no-sanitizers" ] && sanitizers=0

tested() {  # ctest with the preset's filter; prints how long the tests took
  local started=$SECONDS
  ctest --preset "$1" -j2
  echo "test.sh: $1 tests passed in $((SECONDS - started)) s"
}
tools/bootstrap.sh --preset release
tested release
if [ "$sanitizers" -eq 1 ]; then
  tools/bootstrap.sh --preset debug-asan
  tested debug-asan
fi
