#!/usr/bin/env bash
# The gpucc tier: compiles every kernel variant (clpt kernels emit, host/tools/kernel_variants.h)
# for two GPU targets with clang-14 and libclc-14, without a GPU, and tabulates what the
# compiler reports per kernel (docs/gpu-compilers.md says what these figures can and cannot tell).
#
#   gpu_compile.sh [--budget FILE] [--record FILE] [--docs FILE] CLPT_BINARY OUTDIR
#       Emits the variants into OUTDIR/src, compiles each for
#         amdgcn-gfx906  amdgcn, -mcpu=gfx906 (Vega 20), with libclc's amdgcn--amdhsa.bc: assembly
#         nvptx64        nvptx64, sm_60 PTX, with libclc's nvptx64--nvidiacl.bc
#       with the variant's own build options (NAME.options) and -Wall -Wextra -Werror: any
#       warning or error fails. Writes OUTDIR/gpu-kernels.tsv, one row per variant, target and
#       kernel (columns below; blank where the target does not report the figure) and the same
#       as a markdown table, OUTDIR/gpu-kernels.md.
#       --budget FILE  then compares the table with FILE (as --compare does); exit 1 on any excess.
#       --record FILE  then writes the table's figures to FILE as the new budget (never run by a
#                      test: re-recording is a decision, e.g. after a deliberate kernel change:
#                      scripts/gpu_compile.sh --record tests/gpucc/budget.tsv build/clpt build/gpucc)
#       --docs FILE    then writes the markdown table with its provenance (command, machine,
#                      compiler versions, date) to FILE, e.g. docs/gpu-kernels.md.
#   gpu_compile.sh --compare BUDGET TSV
#       Only the budget check of a table already written: exit 1, printing the offending rows,
#       when a kernel's VGPRs, SGPRs, scratch or local-depot bytes exceed BUDGET's, or when a
#       (variant, target, kernel) is in one file and not in the other (so the budget stays current).
#
# Table columns (TAB-separated, header first):
#   variant target kernel vgpr sgpr scratch_bytes occupancy local_depot_bytes
#   vgpr, sgpr     amdgcn: registers per work-item (VGPRs) and per wave (SGPRs), "; NumVgprs:" and
#                  "; NumSgprs:" of the kernel's "; Kernel info:" block in the assembly
#   scratch_bytes  amdgcn: private memory spilled or allocated per work-item ("; ScratchSize:")
#   occupancy      amdgcn: waves per SIMD the register use allows, of 10 on gfx906 ("; Occupancy:")
#   local_depot_bytes  nvptx64: the .entry's __local_depot array (private memory in local, i.e.
#                  off-chip, memory), 0 if it has none. PTX declares virtual registers (.reg
#                  %f<N>) without a limit; ptxas allocates the real ones when the driver loads the
#                  PTX, so nothing here counts NVIDIA registers.
# Budget columns: variant target kernel max_vgpr max_sgpr max_scratch_bytes max_local_depot_bytes
set -euo pipefail

CLANG=${CLPT_CLANG:-clang-14}
CLC_DIR=${CLPT_LIBCLC_DIR:-/usr/lib/clc}
AMD_CPU=gfx906
NV_CPU=sm_60

die() { printf 'gpu_compile.sh: %s\n' "$*" >&2; exit 2; }
usage() { sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//' >&2; exit 2; }

# compare BUDGET TSV: prints every row that breaks the budget; returns 1 if any.
compare() {
  local budget=$1 table=$2
  [[ -f $budget ]] || die "no budget file '$budget' (record one with --record)"
  [[ -f $table ]] || die "no table '$table'"
  awk -F'\t' '
    function over(what, have, limit) {
      if (have != "" && limit != "" && have + 0 > limit + 0) {
        printf "OVER BUDGET  %s  %s: %s > %s\n", key, what, have, limit; bad = 1
      }
    }
    FNR == 1 { next }  # headers
    NR == FNR { key = $1 "\t" $2 "\t" $3; vgpr[key] = $4; sgpr[key] = $5; scratch[key] = $6; depot[key] = $7; next }
    {
      key = $1 "\t" $2 "\t" $3; seen[key] = 1
      if (!(key in vgpr)) { printf "NOT IN BUDGET  %s  (re-record the budget)\n", key; bad = 1; next }
      over("vgpr", $4, vgpr[key]); over("sgpr", $5, sgpr[key])
      over("scratch_bytes", $6, scratch[key]); over("local_depot_bytes", $8, depot[key])
    }
    END {
      for (key in vgpr) if (!(key in seen)) { printf "NOT COMPILED  %s  (in the budget only; re-record it)\n", key; bad = 1 }
      exit bad
    }' "$budget" "$table"
}

if [[ ${1:-} == --compare ]]; then
  [[ $# -eq 3 ]] || usage
  if compare "$2" "$3"; then echo "gpu_compile.sh: every kernel within $2"; exit 0; fi
  echo "gpu_compile.sh: kernels over the budget $2 (rows above)" >&2
  exit 1
fi

budget="" record="" docs=""
while [[ $# -gt 0 && $1 == --* ]]; do
  case $1 in
    --budget) budget=${2:?--budget needs a file}; shift 2 ;;
    --record) record=${2:?--record needs a file}; shift 2 ;;
    --docs) docs=${2:?--docs needs a file}; shift 2 ;;
    -h|--help) usage ;;
    *) die "unknown option '$1'" ;;
  esac
done
[[ $# -eq 2 ]] || usage
clpt=$1 out=$2
[[ -x $clpt ]] || die "'$clpt' is not an executable clpt binary (build it first)"

# The tools, with the Debian package that provides each.
command -v "$CLANG" >/dev/null || die "'$CLANG' not found: install the Debian package clang-14 (apt-get install clang-14)"
for lib in amdgcn--amdhsa.bc nvptx64--nvidiacl.bc; do
  [[ -f $CLC_DIR/$lib ]] || die "libclc bitcode '$CLC_DIR/$lib' not found: install the Debian package libclc-14 (apt-get install libclc-14)"
done

here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
rm -rf "$out/src" "$out/amdgcn-$AMD_CPU" "$out/nvptx64" && mkdir -p "$out/src" "$out/amdgcn-$AMD_CPU" "$out/nvptx64"
"$clpt" kernels emit "$out/src" --scene "$here/scenes/diffuse.toml"
mapfile -t variants < <(cut -d' ' -f1 "$out/src/variants.txt")
[[ ${#variants[@]} -gt 0 ]] || die "clpt kernels emit listed no variants"

# Each target links libclc's bitcode for it (its builtins: sqrt, native_*, atomics, work-item
# functions); clang's own OpenCL header declares them. The bitcode is linked as clang links a GPU
# device library (-mlink-builtin-bitcode, not -mlink-bitcode-file): only what the kernels call,
# internalised, and given the kernel's floating-point attributes. With -mlink-bitcode-file the
# library's functions lack "unsafe-fp-math", inlining them strips it from the kernel (LLVM merges
# it with AND), and the fast preset's native_sin/native_cos then cannot be selected on nvptx64.
# The triples are libclc's own (amdgcn-unknown-amdhsa, nvptx64-unknown-nvidiacl; the vendor
# field does not change code generation): with any other spelling, linking warns of mismatched
# triples, which -Werror makes an error. -nogpulib: no ROCm device library (libclc stands in for
# it). nvptx_native.h supplies native_powr, which LLVM 14's NVPTX backend cannot build from
# libclc (see there). A builtin neither resolves stops the backend ("Undefined external symbol").
common=(-x cl -Xclang -finclude-default-header -O3 -S -Wall -Wextra -Werror)
amd=(-target amdgcn-unknown-amdhsa "-mcpu=$AMD_CPU" -nogpulib -Xclang -mlink-builtin-bitcode -Xclang "$CLC_DIR/amdgcn--amdhsa.bc")
nv=(-target nvptx64-unknown-nvidiacl -Xclang -target-cpu -Xclang "$NV_CPU" -include "$here/scripts/gpucc/nvptx_native.h"
    -Xclang -mlink-builtin-bitcode -Xclang "$CLC_DIR/nvptx64--nvidiacl.bc")

# compile_one VARIANT TARGET: one compilation, its diagnostics in OUT/TARGET/VARIANT.log; a
# failure leaves OUT/TARGET/VARIANT.failed (so that no exit status has to be collected twice).
compile_one() {
  local v=$1 target=$2 flags dest
  read -r -a opts <"$out/src/$v.options"
  if [[ $target == nvptx64 ]]; then flags=("${nv[@]}") dest=$out/nvptx64/$v.ptx
  else flags=("${amd[@]}") dest=$out/$target/$v.s; fi
  if ! "$CLANG" "${common[@]}" "${flags[@]}" "${opts[@]}" "$out/src/$v.cl" -o "$dest" >"$out/$target/$v.log" 2>&1; then
    : >"$out/$target/$v.failed"
  fi
}

# All compilations, as many at a time as there are cores.
for v in "${variants[@]}"; do
  for target in "amdgcn-$AMD_CPU" nvptx64; do
    while [[ $(jobs -rp | wc -l) -ge $(nproc) ]]; do wait -n || true; done
    compile_one "$v" "$target" &
  done
done
wait
failed=0
for v in "${variants[@]}"; do
  for target in "amdgcn-$AMD_CPU" nvptx64; do
    [[ -e $out/$target/$v.failed ]] || continue
    failed=1
    # The backend's crash dumps (its DAG and stack) say nothing the first lines do not.
    { printf 'gpu_compile.sh: %s for %s failed:\n' "$v" "$target"; grep -v '^ *0x\|^ *#[0-9]' "$out/$target/$v.log" | head -40; } >&2
  done
done
[[ $failed -eq 0 ]] || die "compilation failed (diagnostics above, whole logs in $out/*/*.log; any warning is an error)"

tsv=$out/gpu-kernels.tsv
printf 'variant\ttarget\tkernel\tvgpr\tsgpr\tscratch_bytes\toccupancy\tlocal_depot_bytes\n' >"$tsv.tmp"
for v in "${variants[@]}"; do
  # amdgcn: each kernel's figures follow its body in a "; Kernel info:" block (in the
  # .AMDGPU.csdata section), right after the ".size NAME, ..." that closes it; the name comes from
  # there, not from the order of kernels. Only .amdhsa_kernel symbols are kernels; a function
  # that was not inlined would print "; Function info:" and is refused (its registers would be
  # counted in its callers' anyway, but a call in these kernels means always_inline failed).
  awk -F'[ \t,]+' -v variant="$v" -v target="amdgcn-$AMD_CPU" '
    /^[ \t]*\.amdhsa_kernel / { kernel[$3] = 1 }
    /^[ \t]*\.size[ \t]/ { fn = $3 }
    /^; Function info:/ { printf "%s: %s: function %s not inlined\n", variant, target, fn > "/dev/stderr"; bad = 1 }
    /^; Kernel info:/ { name = fn; order[++n] = name }
    /^; NumSgprs:/ { sgpr[name] = $3 }
    /^; NumVgprs:/ { vgpr[name] = $3 }
    /^; ScratchSize:/ { scratch[name] = $3 }
    /^; Occupancy:/ { occ[name] = $3 }
    END {
      for (i = 1; i <= n; ++i) {
        k = order[i]
        if (!(k in kernel) || vgpr[k] == "" || sgpr[k] == "" || scratch[k] == "" || occ[k] == "") {
          printf "%s: %s: incomplete kernel info for %s\n", variant, target, k > "/dev/stderr"; bad = 1; continue
        }
        printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\t\n", variant, target, k, vgpr[k], sgpr[k], scratch[k], occ[k]
      }
      if (n == 0) { printf "%s: %s: no kernel info\n", variant, target > "/dev/stderr"; bad = 1 }
      exit bad
    }' "$out/amdgcn-$AMD_CPU/$v.s" >>"$tsv.tmp"
  # nvptx64: ".visible .entry NAME(" opens a kernel, ".func" a device function (refused, as
  # above); a private array or spill lives in ".local .align A .b8 __local_depotN[BYTES];" at the
  # top of the body. Calls to undefined symbols (a builtin libclc lacks) are refused too.
  awk -v variant="$v" -v target=nvptx64 '
    /^\.visible \.entry |^\.entry / { name = $0; sub(/^.*\.entry[ \t]+/, "", name); sub(/\(.*$/, "", name); order[++n] = name; depot[name] = 0 }
    /^(\.visible |\.weak |\.extern )?\.func/ { printf "%s: %s: device function not inlined: %s\n", variant, target, $0 > "/dev/stderr"; bad = 1 }
    /__local_depot[0-9]+\[/ && /\.local/ { b = $0; sub(/^.*__local_depot[0-9]+\[/, "", b); sub(/\].*$/, "", b); depot[name] = b }
    END {
      for (i = 1; i <= n; ++i) printf "%s\t%s\t%s\t\t\t\t\t%s\n", variant, target, order[i], depot[order[i]]
      if (n == 0) { printf "%s: %s: no .entry\n", variant, target > "/dev/stderr"; bad = 1 }
      exit bad
    }' "$out/nvptx64/$v.ptx" >>"$tsv.tmp"
done
mv "$tsv.tmp" "$tsv"
# Both targets must name the same kernels per variant: a parse that lost or misnamed one shows here.
mismatch=$(awk -F'\t' 'NR > 1 { k = $1 " " $3; if ($2 == "nvptx64") nv[k] = 1; else amd[k] = 1 }
  END { for (k in nv) if (!(k in amd)) print "nvptx64 only: " k; for (k in amd) if (!(k in nv)) print "amdgcn only: " k }' "$tsv")
[[ -z $mismatch ]] || die "the targets disagree on the kernels: $mismatch"

# The markdown table: one row per variant and kernel, both targets side by side.
markdown() {
  echo "| variant | kernel | gfx906 VGPRs | gfx906 SGPRs | gfx906 scratch B | gfx906 occupancy (of 10) | nvptx64 local depot B |"
  echo "|---|---|---:|---:|---:|---:|---:|"
  awk -F'\t' '
    NR == 1 { next }
    { key = $1 "\t" $3 }
    !(key in seen) { seen[key] = 1; order[++n] = key }
    $2 ~ /^amdgcn/ { amd[key] = $4 " | " $5 " | " $6 " | " $7 }
    $2 == "nvptx64" { nv[key] = $8 }
    END {
      for (i = 1; i <= n; ++i) {
        split(order[i], f, "\t")
        printf "| %s | %s | %s | %s |\n", f[1], f[2], (order[i] in amd ? amd[order[i]] : " | | | "), nv[order[i]]
      }
    }' "$tsv"
}
markdown >"$out/gpu-kernels.md"
echo "gpu_compile.sh: ${#variants[@]} variants x 2 targets compiled; $tsv"

if [[ -n $docs ]]; then
  cpu=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo)
  virt=$(systemd-detect-virt 2>/dev/null || true)
  {
    echo "# GPU compiler figures per kernel (generated)"
    echo
    echo "Written by \`scripts/gpu_compile.sh --docs docs/gpu-kernels.md build/clpt build/gpucc\`; what the"
    echo "figures mean and what they cannot tell: [gpu-compilers.md](gpu-compilers.md)."
    echo
    echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
    echo "- machine: $(nproc)-core ${cpu:-unknown CPU}${virt:+ (virtualisation: $virt)}, $(. /etc/os-release && echo "$PRETTY_NAME")"
    echo "- compiler: $("$CLANG" --version | head -1); libclc $(dpkg-query -W -f='${Version}' libclc-14 2>/dev/null || echo '(version unknown)')"
    echo "- targets: amdgcn -mcpu=$AMD_CPU (libclc amdgcn--amdhsa.bc), nvptx64 $NV_CPU (libclc nvptx64--nvidiacl.bc), -O3"
    echo "- source: $(git -C "$here" rev-parse --short HEAD 2>/dev/null || echo unknown)$(git -C "$here" diff --quiet HEAD -- kernels host 2>/dev/null || echo ' (with uncommitted changes)')"
    echo
    echo "gfx906 occupancy: waves per SIMD the kernel's registers allow, 10 at most. nvptx64 local depot:"
    echo "private bytes per work-item in off-chip local memory. NVIDIA registers are not known here:"
    echo "PTX declares unlimited virtual registers, which ptxas allocates only when the driver loads it."
    echo
    markdown
  } >"$docs.tmp"
  mv "$docs.tmp" "$docs"
  echo "gpu_compile.sh: wrote $docs"
fi

if [[ -n $record ]]; then
  {
    printf 'variant\ttarget\tkernel\tmax_vgpr\tmax_sgpr\tmax_scratch_bytes\tmax_local_depot_bytes\n'
    awk -F'\t' 'NR > 1 { printf "%s\t%s\t%s\t%s\t%s\t%s\t%s\n", $1, $2, $3, $4, $5, $6, $8 }' "$tsv"
  } >"$record.tmp"
  mv "$record.tmp" "$record"
  echo "gpu_compile.sh: recorded the budget $record"
fi

if [[ -n $budget ]]; then
  if compare "$budget" "$tsv"; then
    echo "gpu_compile.sh: every kernel within $budget"
  else
    echo "gpu_compile.sh: kernels over the budget $budget (rows above); if the growth is deliberate, re-record:" >&2
    echo "  scripts/gpu_compile.sh --record $budget $clpt $out" >&2
    exit 1
  fi
fi
