#!/usr/bin/env bash
# How one render scales over MPI ranks: for K = 1..MAX_RANKS, `mpirun -n K clpt render` of the same
# scene, REPEAT times each, alternating K; the job's paths/s over its passes (the summary's
# second line: every rank's samples over rank 0's wall time of the passes, fixed start-up costs
# excluded), its median, the speed-up over K = 1 and the efficiency (speed-up / K).
#   scripts/mpi_scaling.sh [MAX_RANKS [REPEAT]] [-- RENDER ARGS...]
# Defaults: 2 ranks, 5 repeats, the diffuse scene at 320x240, 64 spp, one PoCL thread per rank
# (POCL_MAX_PTHREAD_COUNT=1; set it to what each rank should use). On a cluster, give mpirun's
# host options through MPIRUN_ARGS (e.g. MPIRUN_ARGS="--hostfile hosts --map-by node").
set -eu
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
clpt=${CLPT:-$root/build/clpt}
max=2 repeat=5
[[ $# -gt 0 && $1 != -- ]] && { max=$1; shift; }
[[ $# -gt 0 && $1 != -- ]] && { repeat=$1; shift; }
[[ $# -gt 0 && $1 == -- ]] && shift
args=("$@")
[[ ${#args[@]} -eq 0 ]] && args=("$root/scenes/diffuse.toml" --width 320 --height 240 --spp 64 --sampler jitter)
export POCL_MAX_PTHREAD_COUNT=${POCL_MAX_PTHREAD_COUNT:-1}
[[ $(id -u) -eq 0 ]] && export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
declare -A rates
for ((r = 0; r < repeat; r++)); do
  for ((k = 1; k <= max; k++)); do
    # shellcheck disable=SC2086  # MPIRUN_ARGS is a list of words
    mpirun ${MPIRUN_ARGS:---oversubscribe --bind-to none} -n $k "$clpt" render "${args[@]}" -o "$out/img.pfm" >"$out/log" 2>&1 ||
      { cat "$out/log"; exit 1; }
    rate=$(sed -n '2s/.*s: \([0-9.]*\) M paths\/s.*/\1/p' "$out/log")
    rates[$k]="${rates[$k]:-} $rate"
  done
done
median() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
echo "| ranks | M paths/s (median of $repeat) | speed-up | efficiency |"
echo "|---|---|---|---|"
base=$(median <<<"${rates[1]}")
for ((k = 1; k <= max; k++)); do
  m=$(median <<<"${rates[$k]}")
  awk -v k=$k -v m="$m" -v b="$base" 'BEGIN {printf "| %d | %.2f | %.2fx | %.0f%% |\n", k, m, m / b, 100 * m / b / k}'
done
