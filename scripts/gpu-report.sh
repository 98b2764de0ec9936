#!/usr/bin/env bash
# The GPU report: on a GPU machine without a package registry, builds clpt from a bundle of
# scripts/offline-bundle.sh and writes a one-page summary with verify, bench, kernel and picture
# files (docs/portability.md, "A GPU report from a machine without a package registry").
#
# scripts/gpu-report.sh BUNDLE OUTDIR [--quick]
#
# On a GPU machine without a package registry (x86-64, the GPU vendor's OpenCL driver, g++ and
# CMake present), from a bundle made by scripts/offline-bundle.sh on a Debian 12 machine: builds
# clpt's render core against the bundle's unpacked packages (no OpenImageIO, no MPI, no tests) and
# writes to OUTDIR, within about 8 minutes on one GPU, eight small files:
#   OUTDIR/summary.md     one page: machine, devices, verify's verdict, the bench table, the
#                         kernels' registers and spills, the first picture, each step's time
#   report.log            everything the steps printed (devices, build, verify, bench, render)
#   verify.json           `clpt verify` of every GPU against the bundle's PoCL films
#   bench.json            `clpt bench`: the book's scenes, the book's scene with 1000 small spheres
#                         (the bundle's scenes/many-spheres.toml) and the mesh scenes, both forms,
#                         every preset
#   traversal.json        `clpt bench --traversal-alone`: the closest-hit queries alone of the mesh
#                         scenes and the 1000 spheres (kernels/trace.cl, no shading), rays/s and
#                         hits per device
#   kernel-budget.tsv     `clpt kernels budget`: the driver's own figures per kernel of every
#                         covering variant (registers and spills where it reports them: NVIDIA)
#   first-picture.pfm     the README's first picture (scripts/render.sh's render) as a raw film,
#   first-picture.var.pfm and its variance; `clpt compare` or any OIIO tool reads them at home
# Where the machine has no GPU it reports on its OpenCL CPU devices instead (CI runs it so on
# PoCL, with --quick: a tiny bench and picture, so the script cannot rot while no GPU is at hand).
# A step that fails is recorded in OUTDIR/summary.md and report.log with its exit status, and the others
# still run; the script exits 1 if any step failed. Work files go to $CLPT_REPORT_WORK (default: a
# temporary directory, removed at the end).
set -uo pipefail

usage() { echo "usage: scripts/gpu-report.sh BUNDLE OUTDIR [--quick]" >&2; exit 2; }
[[ $# -ge 2 ]] || usage
bundle=$(cd "$1" 2>/dev/null && pwd) || { echo "gpu-report: no bundle directory $1" >&2; exit 2; }
mkdir -p "$2" || exit 2
out=$(cd "$2" && pwd)
quick=0
[[ $# -ge 3 ]] && { [[ $3 == --quick ]] && quick=1 || usage; }
for d in prefix src films; do
  [[ -d "$bundle/$d" ]] || { echo "gpu-report: $bundle/$d is missing: not a bundle of scripts/offline-bundle.sh" >&2; exit 2; }
done

# What the steps render: on a GPU, the bench at 640x480 and 256 spp (the H200 ran 64 spp of the
# book's scenes in 10-20 ms, too short a run to time well: docs/performance.md, "GPUs") and the
# first picture as scripts/render.sh renders it; --quick, tiny sizes.
# scenes/many-spheres.toml is the bundle's (scripts/offline-bundle.sh writes it).
scenes=scenes/diffuse.toml,scenes/specular.toml,scenes/glass.toml,scenes/many-spheres.toml,scenes/cornell-box.toml,scenes/torus-knot.toml
traversal_scenes=scenes/cornell-box.toml,scenes/torus-knot.toml,scenes/many-spheres.toml
precisions=fast,robust,double
bench_size=(--width 640 --height 480 --spp 256 --warmup 1 --repeat 3)
traversal_size=(--width 640 --height 480)
picture_size=()
# Each step's time limit, in seconds: within 8 minutes together on a GPU machine (whose build runs
# on many cores); --quick runs on a small CPU machine, whose build alone takes minutes.
limits=(devices=60 build=150 verify=90 bench=180 traversal=30 picture=30 budget=30)
if [[ $quick -eq 1 ]]; then
  limits=(devices=60 build=900 verify=300 bench=300 traversal=120 picture=120 budget=120)
  scenes=scenes/diffuse.toml,scenes/cornell-box.toml
  traversal_scenes=scenes/cornell-box.toml,scenes/many-spheres.toml
  traversal_size=(--width 32 --height 24)
  precisions=robust
  bench_size=(--width 32 --height 24 --spp 1 --warmup 0 --repeat 1)
  picture_size=(--width 32 --height 24 --spp 4)
fi

work=${CLPT_REPORT_WORK:-$(mktemp -d)}
[[ -n ${CLPT_REPORT_WORK:-} ]] || trap 'rm -rf "$work"' EXIT
mkdir -p "$work"
log=$out/report.log
: >"$log"
failed=()
timings=()
say() { printf '%s\n' "$*" | tee -a "$log" >&2; }

# step NAME SECONDS COMMAND...: runs COMMAND with its output appended to report.log, bounded in
# time, and records its wall time and exit status.
step() {
  local name=$1 limit start end status entry
  shift
  for entry in "${limits[@]}"; do [[ ${entry%%=*} == "$name" ]] && limit=${entry#*=}; done
  say "== $name: $*"
  start=$(date +%s.%N)
  timeout "$limit" "$@" >>"$log" 2>&1
  status=$?
  end=$(date +%s.%N)
  local took
  took=$(awk -v a="$start" -v b="$end" 'BEGIN {printf "%.1f", b - a}')
  timings+=("| $name | $took s | $([[ $status -eq 0 ]] && echo ok || echo "exit $status") |")
  [[ $status -eq 0 ]] || failed+=("$name (exit $status)")
  say "== $name: exit $status after $took s"
  write_summary
  return $status
}

# --- The bundle's libraries and the OpenCL drivers ---------------------------------------------
prefix=$bundle/prefix/usr
libdir=$prefix/lib/x86_64-linux-gnu
export LD_LIBRARY_PATH="$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
# The bundle's ICD loader reads /etc/OpenCL/vendors. A container often has NVIDIA's driver
# library mounted without its .icd file there: then list it in a vendors directory of our own,
# beside the system's entries.
vendors=/etc/OpenCL/vendors
if ! grep -qs nvidia "$vendors"/*.icd && ldconfig -p 2>/dev/null | grep -q 'libnvidia-opencl.so.1'; then
  mkdir -p "$work/vendors"
  cp "$vendors"/*.icd "$work/vendors/" 2>/dev/null
  echo libnvidia-opencl.so.1 >"$work/vendors/nvidia.icd"
  export OCL_ICD_VENDORS=$work/vendors
  say "OpenCL: NVIDIA's libnvidia-opencl.so.1 is present without an .icd file; listed in $OCL_ICD_VENDORS"
fi

# The one-page summary, rewritten after every step, so that a run stopped by a time limit still
# leaves one.
write_summary() {
  {
    echo "# clpt GPU report"
    echo
    echo "$(date -u '+%Y-%m-%d %H:%M UTC'); tree $(sed -n 's/^tree: //p' "$bundle/MANIFEST" 2>/dev/null);"
    echo "host: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores; $(. /etc/os-release 2>/dev/null; echo "${PRETTY_NAME:-unknown OS}")"
    echo
    echo "## Devices"
    echo '```'
    sed -n '/^== devices: /,/^== devices: exit/p' "$log" | grep -v '^== '
    echo '```'
    echo "## Verify against the bundle's PoCL films"
    echo '```'
    sed -n '/^== verify: /,/^== verify: exit/p' "$log" | grep -E '^(verify:|FAIL:|reference:|skipped:|clpt: error)' ||
      echo "(no verify output)"
    echo '```'
    echo "## Bench ($scenes; paths/s median, passes only)"
    echo '```'
    sed -n '/^== bench: /,/^== bench: exit/p' "$log" | grep -vE '^(== |    |bench: )' | head -80
    echo '```'
    echo "## Traversal alone ($traversal_scenes; kernels/trace.cl, closest-hit queries without shading)"
    echo '```'
    sed -n '/^== traversal: /,/^== traversal: exit/p' "$log" |
      awk '/^scenes\// {print $1, $2, $3; next} /traversal alone:/ {print}' | cut -c1-150 | head -20
    echo '```'
    echo "## Kernels: the driver's own figures (kernel-budget.tsv)"
    if [[ -s "$out/kernel-budget.tsv" ]]; then
      awk -F'\t' 'NR > 1 {n++; if ($4 != "" && $4 + 0 > reg) {reg = $4 + 0; regk = $1 " " $2}
                          if ($6 != "") {known++; if ($6 + 0 > 0 || $7 + 0 > 0) spills++}
                          if ($8 + 0 > priv) {priv = $8 + 0; privk = $1 " " $2}}
                  END {printf "%d kernels; most registers: %s (%s); spills: %s; most private memory: %d bytes (%s)\n",
                              n, reg ? reg : "not reported", regk,
                              known ? spills " of " known " kernels" : "not reported", priv, privk}' "$out/kernel-budget.tsv"
    else
      echo "(no table)"
    fi
    echo
    echo "## First picture (first-picture.pfm)"
    echo '```'
    sed -n '/^== picture: /,/^== picture: exit/p' "$log" | grep -v '^== ' | tail -6
    echo '```'
    echo
    echo "## Steps"
    echo "| step | wall time | status |"
    echo "|---|---|---|"
    printf '%s\n' "${timings[@]}"
    echo
    echo "Failed steps: ${failed[*]:-none}"
  } >"$out/summary.md"
}

# --- Build --------------------------------------------------------------------------------------
src=$bundle/src
build=$work/build
clpt=$build/clpt
# --quick (CI, 2 cores) builds without optimisation (-O0, which g++ compiles faster): the same
# recipe otherwise, and a tiny report does not need fast host code.
build_type=(-DCMAKE_BUILD_TYPE=Release)
[[ $quick -eq 1 ]] && build_type=(-DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O0)
step build bash -c "cmake -S '$src' -B '$build' ${build_type[*]} -DCLPT_WITH_OIIO=OFF \
    -DCLPT_BUILD_TESTS=OFF -DCLPT_WITH_MPI=OFF -DCLPT_WITH_EMBREE=OFF -DCLPT_ASSIMP_WITHOUT_CONFIG=ON \
    -DCMAKE_PREFIX_PATH='$prefix' -DCMAKE_IGNORE_PREFIX_PATH=/usr -DCMAKE_POLICY_VERSION_MINIMUM=3.5 \
    && cmake --build '$build' -j $(nproc) --target clpt -- -k"
if [[ ! -x $clpt ]]; then
  say "gpu-report: the build failed; see report.log"
  printf '# clpt GPU report\n\nThe build failed; report.log has its output.\n' >"$out/summary.md"
  exit 1
fi
cd "$src" || exit 1

# --- The devices: every GPU, else (no GPU here) every CPU device --------------------------------
step devices "$clpt" devices
gpu_count=$(grep -cE '^\s+\[[0-9]+\] GPU' "$log")
if [[ $gpu_count -gt 0 ]]; then
  devices=$(seq -s, -f 'gpu:%g' 0 $((gpu_count - 1)))
  first=gpu:0
else
  devices=all
  first=cpu
  say "gpu-report: no GPU found; reporting on the CPU devices instead"
fi

# --- Verify, bench, the first picture, the kernels' budget ---------------------------------------
step verify "$clpt" verify --device "$devices" --reference films --reference-dir "$bundle/films" \
  --json "$out/verify.json"
step bench "$clpt" bench --devices "$devices" --scenes "$scenes" --forms megakernel,wavefront \
  --precisions "$precisions" "${bench_size[@]}" --json "$out/bench.json"
# The traversal alone on the mesh scenes and the 1000 spheres (a hierarchy on GPUs;
# docs/performance.md, "Traversal"): one tiny render per row, then 0.5 s of closest-hit queries on
# the statistics' rays.
step traversal "$clpt" bench --devices "$devices" --scenes "$traversal_scenes" --forms megakernel --precisions robust \
  --traversal-alone --no-vector-width "${traversal_size[@]}" --spp 1 --warmup 0 --repeat 1 --json "$out/traversal.json"
# scripts/render.sh's render of the default scene (README's first picture), as a raw film.
step picture "$clpt" render scenes/diffuse.toml --device "$first" --estimator nee --sampler sobol \
  --target-error 0.1 "${picture_size[@]}" -o "$out/first-picture.pfm"
step budget bash -c "'$clpt' kernels budget --scene scenes/diffuse.toml --device '$first' >'$out/kernel-budget.tsv'"

say "gpu-report: wrote $(ls "$out" | wc -l) files to $out"
[[ ${#failed[@]} -eq 0 ]]
