#!/usr/bin/env bash
# scripts/time_to_book_error.sh and scripts/film_error.py without the book renderer and without
# timing anything: bad arguments give the usage or a message naming the argument and exit 2; a
# book image that is not the book binary's render exits 1; film_error.py's RMSE takes the
# reference's noise out as documented (and gives the worst pixels' share of the error), and its
# PPM check accepts the book's tone mapping and rejects a value two steps off.
#   time_to_book_error_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
script="$src/scripts/time_to_book_error.sh" film_error="$src/scripts/film_error.py"
export CLPT_BUILD=$(dirname "$clpt")  # the script uses this build's clpt, never builds one
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# expect CODE TEXT COMMAND...: COMMAND exits CODE and its stderr contains TEXT.
expect() {
  local code=$1 text=$2
  shift 2
  "$@" >out.txt 2>err.txt
  local status=$?
  [[ $status -eq $code ]] || fail "$* exited $status, expected $code: $(cat err.txt)"
  grep -qF -- "$text" err.txt || fail "$*: stderr lacks '$text': $(cat err.txt)"
}

# pfm NAME VALUE...: a 2x1 little-endian float RGB PFM holding VALUE... (6 values).
pfm() {
  local name=$1
  shift
  python3 -c 'import array, sys; a = array.array("f", map(float, sys.argv[2:]));
sys.byteorder == "little" or a.byteswap()
with open(sys.argv[1], "wb") as f: f.write(b"PF\n2 1\n-1.0\n" + a.tobytes())' "$name" "$@"
}
pfm image.pfm 0.5 0.5 0.5 0.5 0.5 0.5
pfm ref.pfm 0.4 0.4 0.4 0.4 0.4 0.4
pfm ref.var.pfm 0.0036 0.0036 0.0036 0.0036 0.0036 0.0036
printf 'P3\n2 1\n255\n186 186 186 186 186 186 ' >match.ppm   # 0.5^(1/2.2) * 255 + 0.5 = 186.6
printf 'P3\n2 1\n255\n186 186 186 186 186 188 ' >off.ppm

# film_error.py: raw RMSE 0.1; minus the reference's variance 0.0036: sqrt(0.01 - 0.0036) = 0.08.
out=$(python3 "$film_error" rmse image.pfm ref.pfm) || fail "film_error.py rmse exited $?"
read -r _ rmse _ raw _ noise _ pixels _ top <<<"$out"
awk -v r="$rmse" -v w="$raw" -v n="$noise" 'BEGIN {exit !(r > 0.07999 && r < 0.08001 && w > 0.09999 && w < 0.10001 && n > 0.00359 && n < 0.00361)}' ||
  fail "film_error.py rmse: '$out', expected rmse 0.08 raw_rmse 0.1 reference_noise 0.0036"
[[ $pixels == 2 ]] || fail "film_error.py rmse counted $pixels pixels, expected 2"
[[ $top == 0.5 ]] || fail "film_error.py rmse: top_share $top, expected 0.5 (one of two equal pixels)"
python3 "$film_error" ppm-match image.pfm match.ppm >out.txt || fail "ppm-match rejected the book's tone mapping: $(cat out.txt)"
python3 "$film_error" ppm-match image.pfm off.ppm >out.txt && fail "ppm-match accepted a value 2 steps off: $(cat out.txt)"
grep -q 'differ 1 max_step 2' out.txt || fail "ppm-match report: $(cat out.txt)"
printf 'Pf\n2 1\n-1.0\n12345678' >not.pfm   # a one-channel PFM
expect 2 "not.pfm: not a 3-channel float PFM" python3 "$film_error" rmse not.pfm ref.pfm
expect 2 "lonely.pfm" python3 "$film_error" rmse image.pfm lonely.pfm
expect 2 "usage" python3 "$film_error" rms image.pfm ref.pfm

# The script's arguments.
printf '#!/bin/sh\ncp "%s/off.ppm" image.ppm\n' "$work" >book && chmod +x book
expect 2 "BOOK_BINARY BOOK_IMAGE.pfm REFERENCE.pfm" "$script"
expect 2 "BOOK_BINARY BOOK_IMAGE.pfm REFERENCE.pfm" "$script" book image.pfm
expect 2 "BOOK_BINARY nobook: no such executable file" "$script" nobook image.pfm ref.pfm
expect 2 "BOOK_BINARY match.ppm: no such executable file" "$script" match.ppm image.pfm ref.pfm
expect 2 "missing.pfm: no such .pfm file" "$script" ./book missing.pfm ref.pfm
expect 2 "match.ppm: no such .pfm file" "$script" ./book image.pfm match.ppm
cp image.pfm lonely.pfm
expect 2 "lonely.var.pfm: no such .pfm file" "$script" ./book image.pfm lonely.pfm
expect 2 "RUNS must be a positive whole number, not '0'" "$script" ./book image.pfm ref.pfm 0
expect 2 "RUNS must be a positive whole number, not 'five'" "$script" ./book image.pfm ref.pfm five
expect 2 "unexpected argument 'x'" "$script" ./book image.pfm ref.pfm 3 x
expect 2 "option set '--spp 8': --time, --spp and -o are the script's own" "$script" ./book image.pfm ref.pfm 3 -- "--spp 8"
expect 2 "--time, --spp and -o" "$script" ./book image.pfm ref.pfm -- "--estimator nee" "--time 2"
# A book image that is not the binary's render (its PPM has one value 2 steps off) stops before
# any clpt render.
expect 1 "image.pfm is not the render of" "$script" ./book image.pfm ref.pfm 1 -- "--estimator nee --sampler sobol"

[[ $failures -eq 0 ]] && echo "time_to_book_error_cli: all checks passed"
exit $((failures > 0))
