#!/usr/bin/env bash
# Malformed glTF files through the real `clpt render` (issue 33 item 6): tests/gltf_corpus.py
# writes one file per error class of docs/gltf.md with the message expected; each must exit 3,
# print "clpt: error: FILE: ELEMENT: ..." (the expected text a prefix of it) and leave no output.
# An unknown --camera is a usage error (exit 2) that lists the file's cameras.
#   gltf_bad_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work/bad" "$work/good" "$work/out"
failures=0 checked=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
python3 "$src/tests/gltf_corpus.py" bad "$work/bad" || fail "gltf_corpus.py bad failed"
python3 "$src/tests/gltf_corpus.py" good "$work/good" || fail "gltf_corpus.py good failed"

# expect_refused CODE MESSAGE_PREFIX ARGS...: clpt exits CODE, stderr starts with the prefix, no output.
expect_refused() {
  local code=$1 prefix=$2 err status
  shift 2
  err=$("$clpt" "$@" -o "$work/out/out.exr" 2>&1 >/dev/null)
  status=$?
  checked=$((checked + 1))
  [[ $status -eq $code ]] || fail "clpt $*: exit $status, expected $code ($err)"
  [[ "$err" == "$prefix"* ]] || fail "clpt $*: message '$err', expected it to start with '$prefix'"
  if [[ -n "$(ls -A "$work/out")" ]]; then
    fail "clpt $*: left $(ls "$work/out")"
    rm -f "$work/out"/*
  fi
}

while IFS=$'\t' read -r name expected; do
  expect_refused 3 "clpt: error: $work/bad/$name: $expected" render "$work/bad/$name"
done <"$work/bad/expect.tsv"
expect_refused 2 "clpt: error: --camera 5: no camera of the scene has that index or name (the file's cameras: 0 'view' (nodes[4]))" \
    render "$work/good/lit.glb" --camera 5
echo "$checked refusals checked, $failures failures"
[[ $failures -eq 0 ]]
