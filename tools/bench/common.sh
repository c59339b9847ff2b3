# Sourced by the benchmark scripts (after `cd` to the repository root): sets `laguerre`, the program
# to run ($LAGUERRE_EXE if set, else the release preset's build, made by tools/bootstrap.sh with the
# program only), and `dir`, a scratch folder removed when the script exits.
if [ -n "${LAGUERRE_EXE:-}" ]; then
  laguerre=$LAGUERRE_EXE
else
  tools/bootstrap.sh --preset release --target laguerre >/dev/null
  laguerre=build/release/tools/laguerre
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
