#!/usr/bin/env bash
# The gpucc budget check (scripts/gpu_compile.sh --compare) on small synthetic tables: within the
# budget it passes; a kernel whose VGPRs, SGPRs, scratch or local-depot bytes grow past the
# budget fails and is printed; so does a kernel in the table but not the budget, or the reverse.
#   gpucc_budget_cli.sh SOURCE_DIR WORK_DIR
set -euo pipefail
src=$1 work=$2
rm -rf "$work" && mkdir -p "$work" && cd "$work"
check=("$src/scripts/gpu_compile.sh" --compare budget.tsv)
tab=$'\t'

cat >budget.tsv <<TSV
variant${tab}target${tab}kernel${tab}max_vgpr${tab}max_sgpr${tab}max_scratch_bytes${tab}max_local_depot_bytes
v1${tab}amdgcn-gfx906${tab}render_paths${tab}100${tab}80${tab}0${tab}
v1${tab}nvptx64${tab}render_paths${tab}${tab}${tab}${tab}0
v1${tab}amdgcn-gfx906${tab}film_sum_jobs${tab}20${tab}19${tab}16${tab}
v1${tab}nvptx64${tab}film_sum_jobs${tab}${tab}${tab}${tab}8
TSV
# table NAME: the budget's figures as a compiled table (occupancy column added), edited by sed.
table() {
  awk -F'\t' 'BEGIN { OFS = "\t" }
    NR == 1 { print "variant", "target", "kernel", "vgpr", "sgpr", "scratch_bytes", "occupancy", "local_depot_bytes"; next }
    { print $1, $2, $3, $4, $5, $6, ($2 ~ /^amdgcn/ ? 3 : ""), $7 }' budget.tsv >"$1"
}
# expect_fail TABLE PATTERN: the check must fail and print a line matching PATTERN.
expect_fail() {
  if "${check[@]}" "$1" >"$1.out" 2>&1; then echo "FAIL: $1 passed the budget"; cat "$1.out"; exit 1; fi
  grep -q -- "$2" "$1.out" || { echo "FAIL: $1: no line matching '$2' in:"; cat "$1.out"; exit 1; }
}

table same.tsv
"${check[@]}" same.tsv
# Fewer registers and bytes than recorded pass (the budget is a ceiling).
table less.tsv && sed -i 's/\t100\t80\t0\t/\t90\t70\t0\t/; s/\t8$/\t0/' less.tsv
"${check[@]}" less.tsv

table vgpr.tsv && sed -i 's/\t100\t80\t/\t101\t80\t/' vgpr.tsv
expect_fail vgpr.tsv $'OVER BUDGET  v1\tamdgcn-gfx906\trender_paths  vgpr: 101 > 100'
table sgpr.tsv && sed -i 's/\t20\t19\t/\t20\t20\t/' sgpr.tsv
expect_fail sgpr.tsv $'film_sum_jobs  sgpr: 20 > 19'
table scratch.tsv && sed -i 's/\t100\t80\t0\t/\t100\t80\t4\t/' scratch.tsv
expect_fail scratch.tsv $'render_paths  scratch_bytes: 4 > 0'
table depot.tsv && sed -i 's/\t8$/\t16/' depot.tsv
expect_fail depot.tsv $'nvptx64\tfilm_sum_jobs  local_depot_bytes: 16 > 8'
table extra.tsv && printf 'v2\tnvptx64\twf_shade\t\t\t\t\t0\n' >>extra.tsv
expect_fail extra.tsv $'NOT IN BUDGET  v2\tnvptx64\twf_shade'
table missing.tsv && sed -i '/film_sum_jobs/d' missing.tsv
expect_fail missing.tsv $'NOT COMPILED  v1\tamdgcn-gfx906\tfilm_sum_jobs'
echo "gpucc budget check: all cases as expected"
