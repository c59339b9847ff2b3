#!/usr/bin/env bash
# Sets everything up and runs the whole default test suite:
#   1. the Release build (warnings as errors) and every test except the `slow` label;
#   2. the Debug build with AddressSanitizer + UndefinedBehaviorSanitizer and the `unit` tests.
#   tools/test.sh [--no-sanitizers]
set -euo pipefail
cd "$(dirname "$0")/.."
sanitizers=1
[ "${1:-}" = "--no-sanitizers" ] && sanitizers=0

tools/bootstrap.sh --preset release
ctest --preset release -j2
if [ "$sanitizers" -eq 1 ]; then
  tools/bootstrap.sh --preset debug-asan
  ctest --preset debug-asan -j2
fi
