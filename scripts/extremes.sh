#!/usr/bin/env bash
# The numerical-extremes matrix (README "Numerical extremes"): renders every extreme scene in each
# precision preset on the test device and prints a markdown table (preset x extreme: pass/fail and
# the worst relative error), also written to OUT (default out/extremes.md). Exit 1 when a result
# contradicts the recorded expectations.
#   scripts/extremes.sh [OUT] [--presets fast,robust,double] [--only SUBSTRING]
# CLPT_TEST_DEVICE picks the device (default: the first CPU device, PoCL here).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"

out=$CLPT_ROOT/out/extremes.md
if [[ $# -gt 0 && $1 != --* ]]; then
  out=$1
  shift
fi
mkdir -p "$(dirname "$out")"
clpt_install_missing "${CLPT_PACKAGES[@]}" "${CLPT_TEST_PACKAGES[@]}"
clpt_build -DCLPT_BUILD_TESTS=ON
# Written beside OUT, then renamed: a failed run leaves no half-written table under OUT.
tmp="$(dirname "$out")/.$(basename "$out").tmp-$$"
trap 'rm -f "$tmp"' EXIT
status=0
"$CLPT_BUILD/tests/clpt_extremes_matrix" --out "$tmp" "$@" || status=$?
if [[ -f "$tmp" ]]; then
  mv "$tmp" "$out"
  echo "wrote $out" >&2
fi
exit $status
