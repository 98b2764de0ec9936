# Shared set-up for scripts/render.sh and scripts/test.sh: install the Debian packages clpt needs
# (only the missing ones), then configure and build. Sourced, not run.

CLPT_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
CLPT_BUILD=${CLPT_BUILD:-$CLPT_ROOT/build}

# What each package is for is in README.md ("Dependencies").
CLPT_PACKAGES=(cmake g++ make ocl-icd-opencl-dev opencl-c-headers pocl-opencl-icd
               libopenimageio-dev openimageio-tools libopenexr-dev libpng-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev gnuplot-nox
               libopenmpi-dev openmpi-bin python3)
# Tests: GoogleTest; python3 checks the JSON and CSV that bench, compare and tradeoff write;
# Oclgrind is the second OpenCL implementation (label xdev); clang-14 with libclc-14 compiles the
# kernels for NVIDIA (nvptx64) and AMD (amdgcn) targets (label gpucc).
CLPT_TEST_PACKAGES=(libgtest-dev python3 oclgrind clang-14 libclc-14)
# scripts/fuzz.sh (libFuzzer needs clang and its runtime libraries; assimp's test models seed the
# mesh-file fuzzer).
CLPT_FUZZ_PACKAGES=(clang libclang-rt-14-dev assimp-testmodels)
# Mesh files of [[mesh]] tables (host/scene/mesh_file.cpp).
CLPT_PACKAGES+=(libassimp-dev)
# glTF scenes (host/scene/gltf_*.cpp, docs/gltf.md): tinygltf, header-only, over nlohmann-json.
CLPT_PACKAGES+=(libtinygltf-dev)

clpt_log() { printf 'clpt: %s\n' "$*" >&2; }

# clpt_install_missing PACKAGE...: apt-get installs those not installed yet, as root or via sudo.
clpt_install_missing() {
  local missing=() p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [[ ${#missing[@]} -eq 0 ]] && return 0
  local sudo=()
  if [[ $(id -u) -ne 0 ]]; then
    if command -v sudo >/dev/null && sudo -n true 2>/dev/null; then
      sudo=(sudo)
    else
      clpt_log "these Debian packages are missing: ${missing[*]}"
      clpt_log "install them as root (apt-get install ${missing[*]}) or give this user sudo, then re-run"
      exit 1
    fi
  fi
  clpt_log "installing missing packages: ${missing[*]}"
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# clpt_generate_meshes: writes the generated meshes of scenes/torus-knot.toml and
# scenes/dense-surface.toml if they are missing (scripts/make_mesh_scene.py,
# scripts/make_dense_mesh_scene.py; python3 is in CLPT_PACKAGES for them: a minimal Debian 12 has none).
clpt_generate_meshes() {
  [[ -f "$CLPT_ROOT/scenes/meshes/torus_knot.ply" ]] || python3 "$CLPT_ROOT/scripts/make_mesh_scene.py" >&2
  [[ -f "$CLPT_ROOT/scenes/meshes/dense_surface.ply" ]] || python3 "$CLPT_ROOT/scripts/make_dense_mesh_scene.py" >&2
}

# clpt_build [CMAKE_ARGS...]: configure (Release) and build everything in $CLPT_BUILD.
# clpt_compiler_launcher: the CMake options that put ccache in front of the compilers when the
# machine has it (a developer's machine or CI; it is no dependency and never installed here), so a
# clean clone rebuilds what an earlier build compiled in seconds; nothing otherwise.
clpt_compiler_launcher() {
  command -v ccache >/dev/null 2>&1 && printf '%s\n' -DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache
  return 0
}

clpt_build() {
  local launcher
  mapfile -t launcher < <(clpt_compiler_launcher)
  cmake -S "$CLPT_ROOT" -B "$CLPT_BUILD" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" >/dev/null
  cmake --build "$CLPT_BUILD" -j "$(nproc)"
}

# clpt_wall_seconds DIR COMMAND...: prints the wall seconds of one whole-process run of COMMAND in
# DIR, its output discarded. A failing run prints its command and exit status on stderr and
# returns 1, so `t=$(clpt_wall_seconds ...)` stops a `set -e` script instead of timing a failure.
clpt_wall_seconds() {
  local dir=$1 start end status=0
  shift
  start=$(date +%s.%N)
  (cd "$dir" && "$@" >/dev/null 2>&1) || status=$?
  end=$(date +%s.%N)
  [[ $status -eq 0 ]] || { clpt_log "failed (exit $status): $*"; return 1; }
  awk -v a="$start" -v b="$end" 'BEGIN {printf "%.3f\n", b - a}'
}

# clpt_median: the median of the numbers on stdin, one a line.
clpt_median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

# clpt_machine_line: "machine: CPU MODEL, N cores; YYYY-MM-DD" for a timing script's report.
clpt_machine_line() {
  printf 'machine: %s, %s cores; %s\n' "$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)" "$(nproc)" "$(date -u +%Y-%m-%d)"
}
