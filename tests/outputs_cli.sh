#!/usr/bin/env bash
# Every command that writes a file, with each of its output options given
#  (a) a bare name in the current directory (the case that once crashed scene-transform with
#      "cannot make absolute path"),
#  (b) a name in another existing directory,
#  (c) a place where no file can be made: under a regular file (which stops root too), in a
#      directory that does not exist, and the name of an existing directory (an output directory:
#      a regular file, or one that does not exist).
# (a) and (b) exit 0 and write every file; (c) exits 5 (the output error) before any work, naming
# the option and the path, and writes nothing. No temporary file (.NAME.clpt-tmp-PID.EXT,
# util/atomic_file.h) is ever left behind.
#   outputs_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work/sub" "$work/inputs" && cd "$work" || exit 1
scene="$src/scenes/diffuse.toml"
mesh_scene="$src/scenes/torus-knot.toml"  # names a mesh file: scene-transform rewrites its path
[[ -f "$src/scenes/meshes/torus_knot.ply" ]] || python3 "$src/scripts/make_mesh_scene.py" >/dev/null ||
  { echo "FAIL: could not make the torus knot mesh"; exit 1; }
touch afile  # a regular file: afile/NAME cannot be made, not even by root
mkdir adir adir.exr adir.pfm adir.json adir.png adir.csv  # existing directories given as output names
export POCL_WORK_GROUP_SPECIALIZATION=0  # one work-group function per kernel: a faster test
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
tiny=(--width 16 --height 12 --sampler jitter)

# Small inputs for compare and tradeoff.
"$clpt" render "$scene" "${tiny[@]}" --spp 64 --seed 1 -q -o inputs/a.exr || { echo "FAIL: input render"; exit 1; }
"$clpt" render "$scene" "${tiny[@]}" --spp 64 --seed 2 -q -o inputs/b.exr || { echo "FAIL: input render"; exit 1; }

no_temporaries() {
  local left
  left=$(find . -name '*.clpt-tmp-*')
  [[ -z "$left" ]] || fail "$1: temporary files left behind: $left"
}

# succeeds LABEL FILES -- ARGS: clpt ARGS exits 0 and every file of FILES (space-separated) exists
# and is not empty.
succeeds() {
  local label=$1 files=$2
  shift 3
  "$clpt" "$@" >out.txt 2>err.txt
  local status=$?
  [[ $status -eq 0 ]] || { fail "$label: clpt $* exited $status: $(cat err.txt)"; return; }
  for f in $files; do [[ -s "$f" ]] || fail "$label: clpt $* did not write $f"; done
  no_temporaries "$label"
  echo "ok: $label"
}

# refuses LABEL OPTION PATH -- ARGS: clpt ARGS exits 5, naming OPTION PATH, and writes nothing.
refuses() {
  local label=$1 option=$2 path=$3
  shift 4
  local before after
  before=$(find . | sort)
  "$clpt" "$@" >out.txt 2>err.txt
  local status=$?
  after=$(find . | sort)
  [[ $status -eq 5 ]] || fail "$label: clpt $* exited $status, expected 5: $(cat err.txt)"
  grep -qF -- "$option $path:" err.txt || fail "$label: the message does not name '$option $path': $(cat err.txt)"
  [[ "$before" == "$after" ]] || fail "$label: clpt $* wrote: $(diff <(echo "$before") <(echo "$after") | grep '^>')"
  [[ $status -eq 5 ]] && echo "ok: $label -> 5: $(cat err.txt)"
}

# Each command with every output in DIR ("" for the current directory).
run_all_in() {
  local d=$1 where=${1:-here}
  succeeds "render .exr + --checkpoint, $where" "${d}r.exr ${d}r.png ${d}r.ckpt" -- \
    render "$scene" "${tiny[@]}" --spp 2 -q -o "${d}r.exr" --checkpoint "${d}r.ckpt"
  succeeds "render .pfm, $where" "${d}p.pfm ${d}p.var.pfm" -- render "$scene" "${tiny[@]}" --spp 2 -q -o "${d}p.pfm"
  succeeds "scene-transform, $where" "${d}far.toml" -- scene-transform "$mesh_scene" --scale 2 -q -o "${d}far.toml"
  succeeds "compare --json --diff-png, $where" "${d}c.json ${d}c.png" -- \
    compare inputs/a.exr inputs/b.exr --json "${d}c.json" --diff-png "${d}c.png"
  succeeds "bench --json, $where" "${d}b.json" -- bench --scenes "$scene" --width 8 --height 8 --spp 1 --warmup 0 --repeat 1 \
    --no-vector-width --json "${d}b.json"
  succeeds "tradeoff -o --plot, $where" "${d}t.csv ${d}t.png" -- tradeoff "$scene" --reference inputs/a.exr \
    "${tiny[@]}" --form megakernel --budgets 0.02 -q -o "${d}t.csv" --plot "${d}t.png"
  mkdir -p "${d}films"
  succeeds "verify --json --save-reference-films, $where" "${d}v.json ${d}films/films.json" -- \
    verify --device cpu --reference device --scenes diffuse --forms megakernel --precisions robust --width 16 \
    --height 12 --spp 16 -q --json "${d}v.json" --save-reference-films "${d}films"
  mkdir -p "${d}kernels"
  succeeds "kernels emit, $where" "${d}kernels/variants.txt" -- kernels emit "${d}kernels" --scene "$scene"
}

# (a) bare names, (b) names in sub/.
run_all_in ""
run_all_in "sub/"
# The rewritten scene names its mesh file from where it was written, and loads from there.
for f in far.toml sub/far.toml; do
  "$clpt" render "$f" --width 8 --height 6 --spp 1 -q -o inputs/far.pfm || fail "$f does not render"
done
rm -f inputs/far.pfm inputs/far.var.pfm

# (c) under a regular file, in a missing directory, an existing directory as the name.
for bad in afile/x nowhere/x adir; do
  refuses "render -o $bad.exr" -o "$bad.exr" -- render "$scene" "${tiny[@]}" --spp 1 -o "$bad.exr"
  refuses "render -o $bad.pfm" -o "$bad.pfm" -- render "$scene" "${tiny[@]}" --spp 1 -o "$bad.pfm"
  refuses "render --checkpoint $bad" --checkpoint "$bad" -- \
    render "$scene" "${tiny[@]}" --spp 1 -o r2.exr --checkpoint "$bad"
  refuses "scene-transform -o $bad" -o "$bad" -- scene-transform "$scene" --scale 2 -o "$bad"
  refuses "compare --json $bad.json" --json "$bad.json" -- compare inputs/a.exr inputs/b.exr --json "$bad.json"
  refuses "compare --diff-png $bad.png" --diff-png "$bad.png" -- \
    compare inputs/a.exr inputs/b.exr --diff-png "$bad.png"
  refuses "bench --json $bad" --json "$bad" -- bench --scenes "$scene" --width 8 --height 8 --spp 1 --json "$bad"
  refuses "tradeoff -o $bad.csv" -o "$bad.csv" -- \
    tradeoff "$scene" --reference inputs/a.exr "${tiny[@]}" --budgets 0.02 -o "$bad.csv"
  refuses "tradeoff --plot $bad.png" --plot "$bad.png" -- \
    tradeoff "$scene" --reference inputs/a.exr "${tiny[@]}" --budgets 0.02 --plot "$bad.png"
  refuses "verify --json $bad.json" --json "$bad.json" -- verify --scenes diffuse --json "$bad.json"
done
refuses "kernels emit afile" "kernels emit" afile -- kernels emit afile --scene "$scene"
refuses "kernels emit nowhere" "kernels emit" nowhere -- kernels emit nowhere --scene "$scene"
refuses "verify --save-reference-films afile" --save-reference-films afile -- \
  verify --reference device --scenes diffuse --save-reference-films afile
refuses "verify --save-reference-films nowhere" --save-reference-films nowhere -- \
  verify --reference device --scenes diffuse --save-reference-films nowhere
no_temporaries "the refused outputs"

if [[ $failures -ne 0 ]]; then
  echo "$failures output case(s) failed"
  exit 1
fi
echo "every command wrote bare names and names in another directory, and refused unwritable ones"
