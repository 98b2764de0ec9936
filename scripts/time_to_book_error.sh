#!/usr/bin/env bash
# Time to the book renderer's error (W2 of issue 15): how long clpt takes, whole process, to
# render the book's diffuse image as accurately as the book's renderer (gemspt) does at 256 spp,
# against how long gemspt takes for those 256 spp; alternating runs, medians.
#
#   scripts/time_to_book_error.sh BOOK_BINARY BOOK_IMAGE.pfm REFERENCE.pfm [RUNS] [-- OPTION_SET...]
#
# BOOK_BINARY    gemspt built by you outside this tree, rendering its diffuse scene at 640x480 and
#                256 spp (main.cpp's samples-per-subpixel argument 16); it writes image.ppm.
# BOOK_IMAGE.pfm that same render as linear float RGB (a harness of yours that replaces only
#                gemspt's output). Checked here: tone mapped the book's way it must be the PPM the
#                binary writes (scripts/film_error.py ppm-match), else exit 1.
# REFERENCE.pfm  a converged 640x480 render of the same image, with REFERENCE.var.pfm beside it
#                (the variance of each pixel's mean), made outside the tree; docs/performance.md
#                records the one measured with. The reference's own noise is taken out of every
#                error: RMSE = sqrt(mean((x - r)^2) - mean(variance of r)) over all pixels and
#                channels (scripts/film_error.py rmse), an unbiased estimate of the error against
#                the converged image itself.
# RUNS           timed runs of each program (default 5); the book's warm-up run is the check above.
# OPTION_SET     `clpt render` options, one quoted word per set, whose converged image is the
#                book's (same estimator target, max bounces and camera; no --time, whose stop is
#                not repeatable). Default: the sets listed in DEFAULT_SETS below.
#
# For each set the script finds the fewest spp at which clpt's image (scenes/diffuse.toml, 640x480,
# the scene's seed) reaches the book's RMSE: a probe render predicts it from error ~ 1/sqrt(spp),
# then renders bracket and bisect it, to a step of 2% of the spp (16 with the grid sampler, whose
# spp are multiples of 16). Searches write raw films (-o x.pfm); the timed runs write the usual EXR
# and PNG of the same render. Then the rounds alternate: the book's binary, then each set's clpt
# command once, RUNS times; medians of the wall times.
# Exit status: 0 done; 1 a program failed or BOOK_IMAGE is not the binary's render; 2 bad arguments.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
usage() { sed -n '2,30p' "$0" >&2; exit 2; }
bad() { echo "time_to_book_error.sh: $*" >&2; exit 2; }
DEFAULT_SETS=(
  "--estimator book --sampler grid"
  "--estimator book --sampler sobol"
  "--estimator nee --sampler grid"
  "--estimator nee --sampler jitter"
  "--estimator nee --sampler sobol"
  "--estimator nee --sampler sobol --adaptive"
  "--estimator nee --sampler sobol --precision fast"
  "--estimator nee --sampler sobol --rr-from 2"
  "--estimator nee --sampler sobol --precision fast --rr-from 2"
  "--estimator nee --sampler sobol-grid"
  "--estimator nee --sampler sobol-grid --exr-compression none"
  "--estimator nee --sampler sobol-grid --precision fast --exr-compression none"
)

[[ $# -ge 3 ]] || usage
book=$1 book_image=$2 reference=$3
shift 3
runs=5
if [[ $# -gt 0 && $1 != "--" ]]; then runs=$1; shift; fi
[[ $runs =~ ^[1-9][0-9]*$ ]] || bad "RUNS must be a positive whole number, not '$runs'"
if [[ $# -gt 0 ]]; then
  [[ $1 == "--" ]] || bad "unexpected argument '$1' (option sets follow --)"
  shift
fi
sets=("$@")
[[ ${#sets[@]} -gt 0 ]] || sets=("${DEFAULT_SETS[@]}")
[[ -f $book && -x $book ]] || bad "BOOK_BINARY $book: no such executable file"
for image in "$book_image" "$reference" "${reference%.pfm}.var.pfm"; do
  [[ $image == *.pfm && -f $image ]] || bad "$image: no such .pfm file"
done
for set in "${sets[@]}"; do
  [[ $set != *--time* && $set != *--spp* && $set != *-o\ * && $set != *--output* ]] ||
    bad "option set '$set': --time, --spp and -o are the script's own"
done
book=$(realpath "$book") book_image=$(realpath "$book_image") reference=$(realpath "$reference")
clpt="$CLPT_BUILD/clpt"
[[ -x $clpt ]] || clpt_build -DCLPT_BUILD_TESTS=OFF
film_error="$CLPT_ROOT/scripts/film_error.py"
scene="$CLPT_ROOT/scenes/diffuse.toml"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
calc() { awk "BEGIN {printf \"%.6g\", $1}"; }
below() { awk -v a="$1" -v b="$2" 'BEGIN {exit !(a <= b)}'; }  # is a <= b?

# The book's image and its error. The binary's warm-up run writes the PPM checked against it.
wall() { clpt_wall_seconds "$work" "$@"; }
wall "$book" >/dev/null
python3 "$film_error" ppm-match "$book_image" "$work/image.ppm" >"$work/match.txt" ||
  { echo "time_to_book_error.sh: $book_image is not the render of $book: $(cat "$work/match.txt")" >&2; exit 1; }
read -r _ target _ book_raw _ ref_noise _ < <(python3 "$film_error" rmse "$book_image" "$reference")

# rmse_at SPP OPTIONS...: the RMSE of clpt's render at SPP spp.
rmse_at() {
  local spp=$1
  shift
  "$clpt" render "$scene" --spp "$spp" -o "$work/s.pfm" -q "$@" >&2
  python3 "$film_error" rmse "$work/s.pfm" "$reference" | awk '{print $2}'
}

# fewest_spp OPTIONS...: prints "SPP RMSE", the fewest spp found whose RMSE reaches the target.
fewest_spp() {
  local unit=1 probe e spp lo=0 hi=0 hi_e mid step
  # The grid sampler (the scene's own, when no --sampler is given) takes multiples of 16 spp.
  [[ " $* " == *" --sampler grid "* || " $* " != *" --sampler "* ]] && unit=16
  probe=$((4 * unit))
  e=$(rmse_at "$probe" "$@")
  spp=$(awk -v p="$probe" -v e="$e" -v t="$target" -v u="$unit" \
    'BEGIN {n = p * (e / t) ^ 2; n = u * int((n + u - 1e-9) / u); print (n < u) ? u : n}')
  if below "$e" "$target"; then hi=$probe hi_e=$e; else lo=$probe; fi
  while [[ $hi -eq 0 ]]; do  # bracket: the prediction, then 10% more at a time
    ((spp > lo)) || spp=$((lo + unit))
    e=$(rmse_at "$spp" "$@")
    if below "$e" "$target"; then hi=$spp hi_e=$e; else lo=$spp spp=$(((spp * 11 / 10 + unit) / unit * unit)); fi
  done
  while :; do  # bisect [lo, hi] to max(unit, 2% of hi)
    step=$((hi / 50 > unit ? hi / 50 : unit))
    ((hi - lo > step)) || break
    mid=$(((lo + hi) / 2 / unit * unit))
    ((mid > lo && mid < hi)) || break
    e=$(rmse_at "$mid" "$@")
    if below "$e" "$target"; then hi=$mid hi_e=$e; else lo=$mid; fi
  done
  echo "$hi $hi_e"
}

declare -a set_spp set_rmse set_times
for i in "${!sets[@]}"; do
  read -r set_spp[i] set_rmse[i] < <(fewest_spp ${sets[i]})
  echo "searched: ${sets[i]}: ${set_spp[i]} spp, RMSE ${set_rmse[i]}" >&2
done

# Timing: RUNS rounds of the book's binary, then each set's command once.
book_times=()
for ((r = 0; r < runs; ++r)); do
  book_times+=("$(wall "$book")")
  for i in "${!sets[@]}"; do
    # shellcheck disable=SC2086  # an option set is words
    set_times[i]+=" $(wall "$clpt" render "$scene" --spp "${set_spp[i]}" -o "$work/t.exr" -q ${sets[i]})"
  done
done
b=$(printf '%s\n' "${book_times[@]}" | clpt_median)

clpt_machine_line
printf 'book renderer, diffuse 640x480, 256 spp: RMSE %s against the reference (%s before taking out the reference noise %s)\n' \
  "$target" "$book_raw" "$(calc "sqrt($ref_noise)")"
printf '  %s runs, median %s s   runs: %s\n' "$runs" "$b" "${book_times[*]}"
printf '%-52s %6s %9s %9s %9s\n' "clpt option set" "spp" "RMSE" "median s" "book/clpt"
best=0 best_set=""
for i in "${!sets[@]}"; do
  c=$(printf '%s\n' ${set_times[i]} | clpt_median)
  ratio=$(calc "$b / $c")
  printf '%-52s %6s %9s %9s %8.1fx   runs:%s\n' "${sets[i]}" "${set_spp[i]}" "${set_rmse[i]}" "$c" "$ratio" "${set_times[i]}"
  if awk -v a="$ratio" -v b="$best" 'BEGIN {exit !(a > b)}'; then best=$ratio best_set=${sets[i]}; fi
done
printf 'best: %.1fx (%s)\n' "$best" "$best_set"
