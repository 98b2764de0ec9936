#!/usr/bin/env bash
# kernel_ir_compare.sh OLD_CLPT NEW_CLPT [RENDER ARGS...]: what PoCL made of the same render's
# kernels in two builds of clpt, instruction by instruction, where a timing cannot tell a few per
# cent from a shared machine's noise. Each build renders once (64x32, 1 spp, from its own source
# tree's root, clpt's cache off) with PoCL's temporary files kept in a fresh cache; then for each
# kernel the work-group function PoCL runs (`*_workgroup_fast`, vectorised) is disassembled
# (llvm-dis of PoCL's LLVM: Debian's llvm-15, not a dependency of clpt) and compared: its
# instructions, its gathers (llvm.masked.gather: one per lane and field where the lanes read
# different addresses) and its scatters, and the lines that differ after value names, metadata
# and debug references are erased, and then also every integer (struct offsets and strides).
#   scripts/kernel_ir_compare.sh /work/old/build/clpt build/clpt scenes/diffuse.toml --estimator nee
set -euo pipefail
[[ $# -ge 3 ]] || { echo "usage: scripts/kernel_ir_compare.sh OLD_CLPT NEW_CLPT SCENE [RENDER ARGS...]" >&2; exit 2; }
dis=${LLVM_DIS:-$(command -v llvm-dis-15 || ls /usr/lib/llvm-15/bin/llvm-dis 2>/dev/null || true)}
[[ -x $dis ]] || { echo "kernel_ir_compare.sh: llvm-dis of LLVM 15 (PoCL 3.1's) not found: apt-get install llvm-15, or set LLVM_DIS" >&2; exit 2; }
old=$(realpath "$1") new=$(realpath "$2")
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for side in old new; do
  binary=${!side}
  mkdir -p "$work/$side"
  (cd "$(dirname "$(dirname "$binary")")" &&
   POCL_LEAVE_KERNEL_COMPILER_TEMP_FILES=1 POCL_CACHE_DIR="$work/$side/pocl" CLPT_CACHE_DIR="$work/$side/clpt" \
     "$binary" render "$@" --no-cache --width 64 --height 32 --spp 1 --sampler jitter -q -o "$work/$side/image.pfm" \
     >"$work/$side/log" 2>&1) || { echo "kernel_ir_compare.sh: the $side build's render failed:" >&2; tail -n 5 "$work/$side/log" >&2; exit 1; }
  while IFS= read -r bc; do
    kernel=$(basename "$(dirname "$(dirname "$bc")")")
    "$dis" "$bc" -o - 2>/dev/null | awk '/^define .*_workgroup_fast\(/ {f = 1} f {print} f && /^}/ {f = 0}' >"$work/$side/$kernel.ll"
  done < <(find "$work/$side/pocl" -name parallel.bc)
done
normal() {  # value names, metadata and debug references erased; with "int", every integer too
  sed -E -e 's/%[-a-zA-Z$._0-9]+/%v/g' -e 's/![a-z._]+ ![0-9]+//g' -e 's/![0-9]+/!m/g' -e 's/, align [0-9]+//g' "$1" |
    { if [[ $2 == int ]]; then sed -E 's/\b[0-9]+\b/N/g'; else cat; fi; } | grep -v '^ *$' || true
}
printf '%-16s %22s %16s %16s %22s\n' kernel "instructions old/new" "gathers old/new" "scatters old/new" "lines differ (no ints)"
status=0
for f in "$work"/old/*.ll; do
  kernel=$(basename "$f" .ll)
  n=$work/new/$kernel.ll
  [[ -f $n ]] || { echo "$kernel: only in the old build"; status=1; continue; }
  count() { grep -cE "$2" "$1" || true; }
  differ=$(diff <(normal "$f" keep) <(normal "$n" keep) | grep -c '^[<>]' || true)
  differ_int=$(diff <(normal "$f" int) <(normal "$n" int) | grep -c '^[<>]' || true)
  printf '%-16s %10s/%-11s %7s/%-8s %7s/%-8s %10s (%s)\n' "$kernel" "$(count "$f" '^  [%a-z]')" "$(count "$n" '^  [%a-z]')" \
    "$(count "$f" 'masked\.gather')" "$(count "$n" 'masked\.gather')" "$(count "$f" 'masked\.scatter')" \
    "$(count "$n" 'masked\.scatter')" "$differ" "$differ_int"
done
exit $status
