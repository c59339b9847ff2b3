#!/usr/bin/env bash
# Sets everything up and runs the main job on a bundled example: packs a 60-node random Delaunay
# network to LPD (a greedy power embedding), draws it, and routes all ordered pairs with every scheme.
# Output goes to out/quickstart/ (this script's own folder, replaced on each run).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/bootstrap.sh --preset release
mkdir -p out/quickstart
laguerre=build/release/tools/laguerre
graph=scenarios/graphs/delaunay-60.txt
echo
echo "== laguerre pack $graph"
"$laguerre" pack "$graph" -o out/quickstart/delaunay-60 --force
echo
echo "== laguerre route out/quickstart/delaunay-60.json --scheme all --pairs all"
"$laguerre" route out/quickstart/delaunay-60.json --scheme all --pairs all
echo
echo "Picture: out/quickstart/delaunay-60.png (circles green where LPD holds, local power cells in blue)."
