#!/usr/bin/env bash
# Whole-process speed of clpt against the book's renderer (gemspt) on the same machine, measured
# side by side: runs alternate (book, clpt, book, clpt, ...) so that drifting machine speed hits
# both, and the medians of the wall times are compared.
#
#   scripts/speed_vs_book.sh GEMSPT_BINARY SPP [RUNS] [-- extra clpt render options]
#
# GEMSPT_BINARY is the book's renderer built by you, outside this tree, rendering the diffuse
# scene at 640x480 and SPP samples per pixel (its main.cpp with the samples-per-subpixel argument
# set to SPP/16; clpt ships no copy of it and no script that builds it). clpt renders the same
# image: scenes/diffuse.toml, 640x480, SPP spp, on the default device and form.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
[[ $# -ge 2 ]] || { sed -n '2,12p' "$0"; exit 2; }
book=$(realpath "$1") spp=$2 runs=${3:-5}
shift $(( $# >= 3 ? 3 : 2 ))
[[ ${1:-} == "--" ]] && shift
clpt="$CLPT_BUILD/clpt"
[[ -x $clpt ]] || clpt_build -DCLPT_BUILD_TESTS=OFF
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

wall() { clpt_wall_seconds "$work" "$@"; }

book_times=() clpt_times=()
wall "$book" >/dev/null  # warm-up (page cache, PoCL kernel cache)
wall "$clpt" render "$CLPT_ROOT/scenes/diffuse.toml" --spp "$spp" -o "$work/w.exr" -q "$@" >/dev/null
for ((i = 0; i < runs; ++i)); do
  book_times+=("$(wall "$book")")
  clpt_times+=("$(wall "$clpt" render "$CLPT_ROOT/scenes/diffuse.toml" --spp "$spp" -o "$work/c.exr" -q "$@")")
done
b=$(printf '%s\n' "${book_times[@]}" | clpt_median)
c=$(printf '%s\n' "${clpt_times[@]}" | clpt_median)
paths=$((640 * 480 * spp))
clpt_machine_line
printf 'diffuse 640x480, %s spp, %s alternating runs each, median wall seconds (whole process)\n' "$spp" "$runs"
calc() { awk "BEGIN {printf \"%.2f\", $1}"; }
printf '  book renderer: %s s (%s M paths/s)   runs: %s\n' "$b" "$(calc "$paths / $b / 1e6")" "${book_times[*]}"
printf '  clpt:          %s s (%s M paths/s)   runs: %s\n' "$c" "$(calc "$paths / $c / 1e6")" "${clpt_times[*]}"
printf '  speed ratio clpt / book: %sx\n' "$(calc "$b / $c")"
