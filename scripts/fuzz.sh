#!/usr/bin/env bash
# Fuzzes the scene loader with libFuzzer (ASan + UBSan): builds build-fuzz with clang and
# CLPT_FUZZ=ON, then runs tests/fuzz/fuzz_scene_loader on a working copy of the seed corpus
# (scenes/ and tests/scenes/bad/) kept in build-fuzz, so nothing is written into the source tree.
#   scripts/fuzz.sh [SECONDS]     fuzz for SECONDS (default 60)
#   scripts/fuzz.sh --runs N      fuzz N inputs
# Anything after "--" goes to libFuzzer, e.g. scripts/fuzz.sh 600 -- -fork=2
# Exits non-zero if any input crashed, leaked, hit undefined behaviour or timed out; those inputs
# are kept in build-fuzz/fuzz/findings/ (re-run one: build-fuzz/tests/fuzz/fuzz_scene_loader FILE).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
build=${CLPT_FUZZ_BUILD:-$CLPT_ROOT/build-fuzz}

limit=(-max_total_time=60)
case "${1:-}" in
  --runs) limit=(-runs="${2:?--runs needs a count}"); shift 2 ;;
  ''|--) ;;
  *[!0-9]*) echo "usage: scripts/fuzz.sh [SECONDS|--runs N] [-- LIBFUZZER_ARGS...]" >&2; exit 2 ;;
  *) limit=(-max_total_time="$1"); shift ;;
esac
[[ "${1:-}" == "--" ]] && shift

clpt_install_missing "${CLPT_PACKAGES[@]}" "${CLPT_FUZZ_PACKAGES[@]}"
# The harness needs neither OpenImageIO nor the test suite; only the fuzz target is built.
cmake -S "$CLPT_ROOT" -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
      -DCLPT_FUZZ=ON -DCLPT_BUILD_TESTS=OFF -DCLPT_WITH_OIIO=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target fuzz_scene_loader

work=$build/fuzz
corpus=$work/corpus/scene_loader
findings=$work/findings
mkdir -p "$corpus" "$findings"
# The seeds join the working corpus, which keeps what earlier runs learnt.
for seed in "$CLPT_ROOT"/scenes/*.toml "$CLPT_ROOT"/tests/scenes/bad/*.toml; do
  [[ -e "$corpus/${seed##*/}" ]] || cp "$seed" "$corpus/"
done
stamp=$work/.started
touch "$stamp"
log=$work/last_run.log

clpt_log "fuzzing the scene loader (${limit[*]}); log: $log"
status=0
# -timeout: an input taking over 10 s is a finding (a scene must load in milliseconds).
"$build/tests/fuzz/fuzz_scene_loader" "${limit[@]}" -dict="$CLPT_ROOT/tests/fuzz/scene.dict" \
    -max_len=8192 -timeout=10 -print_final_stats=1 -artifact_prefix="$findings/" "$@" \
    "$corpus" >"$log" 2>&1 || status=$?

runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | awk '{s += $2} END {print s + 0}' || true)
secs=$(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | awk '{print $5}' | tail -n 1 || true)
new=()
while IFS= read -r -d '' f; do new+=("$f"); done < <(find "$findings" -type f -newer "$stamp" -print0)
echo "fuzz_scene_loader: ${runs} inputs tried${secs:+ in ${secs} s}, ${#new[@]} crash(es)/leak(s)/timeout(s)," \
     "corpus $(find "$corpus" -type f | wc -l) files"
if [[ ${#new[@]} -gt 0 || $status -ne 0 ]]; then
  grep -E 'ERROR: |runtime error|SUMMARY|fuzz_scene_loader: ' "$log" | head -n 20 >&2 || true
  for f in "${new[@]}"; do echo "  finding: $f"; done
  echo "fuzz_scene_loader: FAILED (exit $status); full log: $log" >&2
  exit 1
fi
