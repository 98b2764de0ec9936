#!/usr/bin/env bash
# Every preset's kernels are vectorised across work-items by PoCL (docs/performance.md,
# "Presets"; docs/design.md lists what stops it): each book scene, and one with a hierarchy, with
# each estimator (every preset on the hierarchy scene, robust on the book's), and the diffuse
# scene with Russian roulette,
# is compiled from source with PoCL's vectoriser remarks on (POCL_VECTORIZER_REMARKS=1, a fresh
# POCL_CACHE_DIR, --no-cache), and the remarks must show a vectorised work-item loop and none of
# the three blockers this code has met: a vector-typed value (LLVM's SLP pairs, e.g. the double
# preset's <2 x double>), a library call, or a switch. Not a timed test: it reads the compiler's
# own account. Skipped (exit 77) when the default device is not PoCL's CPU device.
#   vectorised_cli.sh CLPT SOURCE_DIR WORK_DIR
set -euo pipefail
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$src"
if ! "$clpt" devices 2>/dev/null | grep -q "(default)" ||
   ! "$clpt" devices 2>/dev/null | grep "(default)" | grep -q "pthread"; then
  echo "SKIP: the default device is not PoCL's pthread CPU device"; exit 77
fi
# On CPUs whose LLVM has no fast-gather tuning (Haswell, Broadwell, AMD Zen 1-3:
# docs/performance.md, "CPUs without fast gathers") the kernels read the hit sphere by selects
# (--sphere-reads auto; clpt's own decision, device_lacks_fast_gathers in kernel_options.cpp, read
# here from --explain). That vectorises the robust preset's megakernel on the book scenes, and that
# is what is checked there; the other presets and the hierarchy scene are known to stay scalar on
# those CPUs and are listed, not checked.
slow_gathers=0
if "$clpt" render scenes/diffuse.toml --explain 2>/dev/null | grep -q "hit sphere reads: selects"; then
  slow_gathers=1
  llvm_cpu=$("$clpt" devices 2>/dev/null | grep -o "HSTR: pthread-[^ ,]*" | head -1 | sed 's/.*-linux-gnu-//')
  echo "NOTE: PoCL compiles for LLVM CPU '$llvm_cpu', without fast gathers: only the robust preset on the book scenes is checked"
fi
failed=0
# check_vectorised NAME SCENE [OPTIONS]: a 16x8, 1-sample render compiled from source with the
# remarks on; fails (failed=1) without a vectorised work-item loop or with a blocker's remark.
check_vectorised() {
  local name=$1; shift
  POCL_VECTORIZER_REMARKS=1 POCL_CACHE_DIR=$work/pocl-$name CLPT_CACHE_DIR=$work/clpt-cache \
    "$clpt" render "$@" --no-cache --width 16 --height 8 --spp 1 --sampler jitter -q -o "$work/$name.pfm" \
    > "$work/$name.log" 2>&1 || { echo "FAIL: $name did not render"; cat "$work/$name.log"; failed=1; return; }
  # LLVM prints the remarks one after another, often on one line: one per line first.
  sed 's/<unknown>:0:0: /\n/g' "$work/$name.log" > "$work/$name.remarks"
  grep -q "vectorized loop (vectorization width: " "$work/$name.remarks" ||
    { echo "FAIL: $name: no work-item loop was vectorised"; failed=1; }
  local blocker
  for blocker in "instruction return type cannot be vectorized" "call instruction cannot be vectorized" \
                 "loop contains a switch statement"; do
    if grep -q "$blocker" "$work/$name.remarks"; then
      echo "FAIL: $name: \"$blocker\" (see $work/$name.remarks)"; failed=1
    fi
  done
}
# And a scene with a hierarchy (more spheres than the unrolled loop takes): the lockstep
# megakernel keeps its traversals in regions of their own (docs/performance.md, "Traversal"), so
# the loop and the shading around them must still vectorise.
python3 scripts/many_spheres_scene.py --count 40 "$work/hierarchy.toml"
# The presets change the intersection and number code that every scene shares, so the hierarchy
# scene (the diffuse scene's room and materials, and the traversal) takes all three; the book's
# scenes (their materials' code) the robust preset only (their fast and double cases were 12 cold
# compiles, about 40 s of CI's time, dropped on 2026-12-06).
for scene in diffuse specular glass "$work/hierarchy"; do
  for estimator in book nee; do
    for precision in fast robust double; do
      [[ $scene != /* && $precision != robust ]] && continue
      name=$(basename "$scene").$estimator.$precision
      if [[ $slow_gathers == 1 && ( $precision != robust || $scene == /* ) ]]; then
        echo "not checked on '$llvm_cpu': $name"; continue
      fi
      check_vectorised "$name" "$([[ $scene == /* ]] && echo "$scene" || echo "scenes/$scene").toml" \
        --estimator "$estimator" --precision "$precision"
    done
  done
done
# The Cornell box (32 triangles and a triangle light): its triangles in the unrolled loop
# (kernels/triangle_loop.cl), with SLP held off for its kernels, the whole lockstep body vectorises.
if [[ $slow_gathers == 0 ]]; then
  check_vectorised cornell-box.nee.robust scenes/cornell-box.toml --estimator nee
fi
# Russian roulette with the book estimator (its own uniform, u3, and no paired scattering draws:
# path.cl), which ran scalar until 2026-12-03 (docs/performance.md, "What limits the speed").
if [[ $slow_gathers == 0 ]]; then
  check_vectorised diffuse.book.robust.roulette scenes/diffuse.toml --rr-from 3
fi
# The environment light's image kernels (kernels/environment.cl): the library's acos/atan2/sin/cos
# and SLP-paired pairs once kept them scalar, 20x slower (docs/environment.md, "What it costs").
if [[ $slow_gathers == 0 ]]; then
  for form in megakernel wavefront; do
    check_vectorised environment.nee.robust.$form scenes/environment.toml --estimator nee --form "$form"
  done
fi
# --cpu-vector-bits must reach PoCL's vectoriser (host/cl/pocl_vectoriser.h): with 512 every
# vectorised loop of the kernels is 16 work-items wide, with 256 (LLVM's cost model) none is, in
# both forms, with the robust preset (the double preset's four cases were dropped from CI on
# 2026-12-06: four cold compiles, about 15 s, for the same option path; the matrix above still
# checks that the double preset vectorises). Only on an AVX-512 CPU (elsewhere clpt refuses 512:
# test_kernel_variants).
if grep -qw avx512f /proc/cpuinfo; then
  for form in megakernel wavefront; do
    for precision in robust; do
      for bits in 512 256; do
        name=bits$bits.$form.$precision
        POCL_VECTORIZER_REMARKS=1 POCL_CACHE_DIR=$work/pocl-$name CLPT_CACHE_DIR=$work/clpt-cache \
          "$clpt" render scenes/diffuse.toml --cpu-vector-bits "$bits" --form "$form" --precision "$precision" \
          --no-cache --width 16 --height 8 --spp 1 --sampler jitter -q -o "$work/$name.pfm" > "$work/$name.log" 2>&1 ||
          { echo "FAIL: $name did not render"; cat "$work/$name.log"; failed=1; continue; }
        sed 's/<unknown>:0:0: /\n/g' "$work/$name.log" | grep -o "vectorization width: [0-9]*" | sort | uniq -c \
          > "$work/$name.widths" || true
        wide=$(grep -c "width: 16$" "$work/$name.widths" || true)
        other=$(grep -vc "width: 16$" "$work/$name.widths" || true)
        if [[ $bits == 512 && ( $wide == 0 || $other != 0 ) ]] || [[ $bits == 256 && ( $wide != 0 || $other == 0 ) ]]; then
          echo "FAIL: $name: vectorised loop widths with --cpu-vector-bits $bits:"; cat "$work/$name.widths"; failed=1
        fi
      done
    done
  done
fi
test "$failed" -eq 0
if [[ $slow_gathers == 1 ]]; then
  echo "vectorised: the book scenes x estimator with the robust preset compile to vectorised work-item loops on PoCL ($llvm_cpu)"
else
  echo "vectorised: every book scene and a hierarchy scene x estimator (x preset: diffuse, hierarchy) compile to vectorised work-item loops on PoCL"
fi
