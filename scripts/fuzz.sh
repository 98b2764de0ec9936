#!/usr/bin/env bash
# Fuzzes the scene loader, mesh files and the command-line option parser with libFuzzer (ASan +
# UBSan): builds build-fuzz with clang and CLPT_FUZZ=ON, then runs tests/fuzz/fuzz_scene_loader
# (seeds: scenes/ and tests/scenes/bad/; run in tests/scenes/bad so that the seeds' mesh files
# resolve), tests/fuzz/fuzz_mesh_file (seeds: tests/scenes/meshes/, tests/scenes/bad/meshes/ and
# assimp-testmodels' small OBJ, PLY and STL files, each behind its file-type byte),
# tests/fuzz/fuzz_assimp_mesh (clpt's handling of synthetic aiScenes; no seeds, no dictionary:
# its input is binary), tests/fuzz/fuzz_gltf (glTF files: seeds written by tests/gltf_corpus.py,
# good and bad, and assimp-testmodels' small glTF 2.0 files, each behind its name byte) and
# tests/fuzz/fuzz_options (seeds: a few command lines) on working corpora kept in build-fuzz, so
# nothing is written into the source tree.
# The harnesses run side by side, as many at once as there are processors.
#   scripts/fuzz.sh [SECONDS]     fuzz each harness for SECONDS (default 60)
#   scripts/fuzz.sh --runs N      fuzz N inputs each
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
extra=("$@")

clpt_install_missing "${CLPT_PACKAGES[@]}" "${CLPT_FUZZ_PACKAGES[@]}"
# The harness needs neither OpenImageIO nor the test suite; only the fuzz target is built.
mapfile -t launcher < <(clpt_compiler_launcher)
cmake -S "$CLPT_ROOT" -B "$build" "${launcher[@]}" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
      -DCLPT_FUZZ=ON -DCLPT_BUILD_TESTS=OFF -DCLPT_WITH_OIIO=OFF >/dev/null
cmake --build "$build" -j "$(nproc)" --target fuzz_scene_loader fuzz_mesh_file fuzz_assimp_mesh fuzz_gltf fuzz_options

# Leaks inside assimp are the library's (tests/fuzz/lsan.supp); clpt's own stay findings.
export LSAN_OPTIONS="suppressions=$CLPT_ROOT/tests/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
work=$build/fuzz
findings=$work/findings
mkdir -p "$findings"
failed=0

# fuzz_target NAME DICT SEED...: runs tests/fuzz/NAME on its working corpus in build-fuzz (the
# seeds join it; it keeps what earlier runs learnt) and reports inputs tried and findings; DICT
# "-" for none.
# first_frame_is_assimp LOG: the first stack frame after the last sanitizer or libFuzzer error
# report that names assimp or clpt names assimp. A failed check of AddressSanitizer's allocator
# ("AddressSanitizer: CHECK failed: asan_allocator.cpp", no "ERROR:") is such a report: heap
# metadata overwritten, which only uninstrumented code (assimp) can do without a report of its own.
first_frame_is_assimp() {
  awk '/ERROR: (AddressSanitizer|libFuzzer|LeakSanitizer)|AddressSanitizer: CHECK failed/ {seen = 1; first = ""}
       seen && first == "" && /^ *#[0-9]+ / && /libassimp\.so|clpt::|fuzz_mesh_file\.cpp/ {
         first = ($0 ~ /libassimp\.so/) ? "assimp" : "clpt" }
       END {exit first == "assimp" ? 0 : 1}' "$1"
}

fuzz_target() {
  local name=$1 dict=$2 dict_option=()
  [[ $dict == - ]] || dict_option=(-dict="$dict")
  shift 2
  local corpus=$work/corpus/$name log=$work/$name.log stamp=$work/.started-$name status=0
  mkdir -p "$corpus"
  for seed in "$@"; do
    [[ -e "$corpus/${seed##*/}" ]] || cp "$seed" "$corpus/"
  done
  touch "$stamp"
  clpt_log "fuzzing $name (${limit[*]}); log: $log"
  # -timeout: an input taking over 10 s is a finding (parsing takes milliseconds).
  (cd "$CLPT_ROOT/tests/scenes/bad" &&
   "$build/tests/fuzz/$name" "${limit[@]}" "${dict_option[@]}" -max_len="${max_len:-8192}" -timeout=10 \
      -print_final_stats=1 -artifact_prefix="$findings/$name-" "${extra[@]}" "$corpus") >"$log" 2>&1 || status=$?
  local runs secs new=()
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | awk '{s += $2} END {print s + 0}' || true)
  secs=$(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | awk '{print $5}' | tail -n 1 || true)
  # Its own findings only (-artifact_prefix names them): the harnesses run side by side, and one's
  # finding must not fail another (a mesh-file OOM inside assimp once failed the scene loader's run).
  while IFS= read -r -d '' f; do new+=("$f"); done < <(find "$findings" -maxdepth 1 -type f -name "$name-*" -newer "$stamp" -print0)
  echo "$name: ${runs} inputs tried${secs:+ in ${secs} s}, ${#new[@]} crash(es)/leak(s)/timeout(s)," \
       "corpus $(find "$corpus" -type f | wc -l) files"
  # A crash whose stack reaches assimp before any clpt frame is the library's own (README "Known
  # library crashes and leaks"): reported and kept in findings/library/, not counted as clpt's.
  if [[ ${#new[@]} -eq 1 && $status -ne 0 ]] && first_frame_is_assimp "$log"; then
    mkdir -p "$findings/library"
    mv "${new[0]}" "$findings/library/"
    echo "$name: a crash inside assimp itself (not clpt's; README \"Known library crashes and leaks\"):" \
         "$findings/library/${new[0]##*/}"
    return 0
  fi
  if [[ ${#new[@]} -gt 0 || $status -ne 0 ]]; then
    grep -E 'ERROR: |runtime error|SUMMARY|fuzz_[a-z_]*: ' "$log" | head -n 20 >&2 || true
    for f in "${new[@]}"; do echo "  finding: $f"; done
    echo "$name: FAILED (exit $status); full log: $log" >&2
    return 1
  fi
}

# The harnesses run side by side, one per processor (each is a single process): start_fuzz
# waits for a free processor, then starts fuzz_target in the background; a failed one sets failed.
running=0
start_fuzz() {
  if [[ $running -ge $(nproc) ]]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
  fuzz_target "$@" &
  running=$((running + 1))
}

# Seeds for the option parser: a few real command lines, arguments separated by NUL bytes.
option_seeds=$work/option-seeds
mkdir -p "$option_seeds"
printf 'render\0scenes/diffuse.toml\0--spp\00016\0-o\0out.exr' >"$option_seeds/render"
printf 'render\0s.toml\0--form\0wavefront\0--paths-in-flight\0004096\0--launch-ms\00075' >"$option_seeds/forms"
printf 'bench\0--forms\0megakernel,wavefront\0--spp\0004\0--json\0b.json' >"$option_seeds/bench"
printf 'cache\0clear' >"$option_seeds/cache"

# Seeds for the mesh files: the first byte picks the type, in the order of
# host/scene/mesh_file.cpp mesh_file_extensions() (obj 0, ply 1, glb 2, gltf 3, stl 4).
mesh_seeds=$work/mesh-seeds
mkdir -p "$mesh_seeds"
mesh_type_byte() {
  case "${1,,}" in
    *.obj) printf '\000' ;; *.ply) printf '\001' ;; *.glb) printf '\002' ;; *.gltf) printf '\003' ;; *.stl) printf '\004' ;;
  esac
}
for f in "$CLPT_ROOT"/tests/scenes/meshes/* "$CLPT_ROOT"/tests/scenes/bad/meshes/* \
         /usr/share/assimp/models/{OBJ,PLY,STL}/*; do
  [[ -f "$f" && $(stat -c %s "$f") -le 8000 && -n "$(mesh_type_byte "$f")" ]] || continue
  seed=$mesh_seeds/$(basename "$(dirname "$f")")-$(basename "$f")
  [[ -e "$seed" ]] || { mesh_type_byte "$f"; cat "$f"; } >"$seed"
done

# glTF seeds: the first byte names the file (0: fuzz.glb, 1: fuzz.gltf; fuzz_gltf.cpp). glTF
# files are larger than the other formats' seeds: inputs up to 64 kB.
gltf_seeds=$work/gltf-seeds
mkdir -p "$gltf_seeds/written"
python3 "$CLPT_ROOT/tests/gltf_corpus.py" good "$gltf_seeds/written"
python3 "$CLPT_ROOT/tests/gltf_corpus.py" bad "$gltf_seeds/written"
for f in "$gltf_seeds"/written/*.gl* /usr/share/assimp/models/glTF2/*/*.gl* \
         /usr/share/assimp/models/glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/*.gltf; do
  [[ -f "$f" && $(stat -c %s "$f") -le 65536 ]] || continue
  seed=$gltf_seeds/$(basename "$(dirname "$f")")-$(basename "$f")
  case "${f,,}" in *.glb) byte='\000' ;; *) byte='\001' ;; esac
  [[ -e "$seed" ]] || { printf "$byte"; cat "$f"; } >"$seed"
done
start_fuzz fuzz_scene_loader "$CLPT_ROOT/tests/fuzz/scene.dict" \
    "$CLPT_ROOT"/scenes/*.toml "$CLPT_ROOT"/tests/scenes/bad/*.toml
start_fuzz fuzz_mesh_file "$CLPT_ROOT/tests/fuzz/mesh.dict" "$mesh_seeds"/*
start_fuzz fuzz_assimp_mesh -
max_len=65536 start_fuzz fuzz_gltf "$CLPT_ROOT/tests/fuzz/gltf.dict" "$gltf_seeds"/*.gl*
start_fuzz fuzz_options "$CLPT_ROOT/tests/fuzz/options.dict" "$option_seeds"/*
while [[ $running -gt 0 ]]; do
  wait -n || failed=1
  running=$((running - 1))
done
exit $failed
