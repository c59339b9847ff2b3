#!/usr/bin/env bash
# Sets everything up and runs the quick-start scenario (scenarios/quickstart.yaml): a 60-node random
# Delaunay network packed to LPD by the distributed protocol in the simulator, all ordered pairs routed
# with every scheme, results and a picture. Output goes to out/quickstart/ (its results are replaced on
# each run).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/bootstrap.sh --preset release --target laguerre   # the program only; tools/test.sh builds the rest
laguerre=build/release/tools/laguerre
echo
echo "== laguerre run scenarios/quickstart.yaml -o out/quickstart --force"
"$laguerre" run scenarios/quickstart.yaml -o out/quickstart --force
echo
echo "Picture: out/quickstart/pictures/point-000.png (network, packing green where LPD holds, power diagram, routes)."
