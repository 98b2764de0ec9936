#!/usr/bin/env bash
# Builds clpt and its tests with AddressSanitizer + UndefinedBehaviorSanitizer (CLPT_SANITIZE=ON)
# in build-asan and runs the unit and bad-input tests there. Any report fails the test it occurs
# in: ASan aborts on the first error, UBSan too (-fno-sanitize-recover=undefined).
# Extra arguments go to ctest, e.g. scripts/sanitize.sh -R Scene
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
build=${CLPT_ASAN_BUILD:-$CLPT_ROOT/build-asan}

clpt_install_missing "${CLPT_PACKAGES[@]}" "${CLPT_TEST_PACKAGES[@]}"
# Debug (-O0 -g, assertions on): the sanitized build compiles about twice as fast as with -O2,
# the reports carry line numbers, and the tests' time goes to PoCL building kernels, not host code.
mapfile -t launcher < <(clpt_compiler_launcher)
cmake -S "$CLPT_ROOT" -B "$build" "${launcher[@]}" -DCMAKE_BUILD_TYPE=Debug -DCLPT_SANITIZE=ON \
      -DCLPT_BUILD_TESTS=ON >/dev/null
# Only what the unit and bad-input tests run: the sanitized build compiles slowly, and the stat
# and cross-device executables are not run here. A new executable carrying the unit label must be
# added to this list (or to CLPT_ASAN_TARGETS), else its tests are silently not built.
read -r -a targets <<<"${CLPT_ASAN_TARGETS:-clpt clpt_unit_tests clpt_extremes_unit_tests}"
cmake --build "$build" -j "$(nproc)" --target "${targets[@]}"

# LeakSanitizer stays on for clpt's own code, but the OpenCL driver is loaded into the process
# uninstrumented and keeps memory it never frees: PoCL and the LLVM it runs to compile kernels
# leave megabytes of compiler state behind whenever a kernel is built rather than read from PoCL's
# cache (as in CI, from a clean home). Those allocations are not clpt's, so leaks whose stack
# passes through the driver libraries are suppressed (print_suppressions=0 keeps stderr exactly
# as the bad-input tests expect it). ASan and UBSan themselves stay fully on.
cat >"$build/lsan.supp" <<'SUPP'
leak:libpocl.so
leak:libLLVM
leak:libclang-cpp
leak:libOpenCL.so
SUPP
# intercept_tls_get_addr=0: with the assimp-linked tests, LeakSanitizer's exit-time scan read a
# bogus dynamic-TLS range (0xab0, 32 GiB, "Tracer caught signal 11") and aborted the process;
# without the interception it scans static TLS and the stacks as before.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:intercept_tls_get_addr=0}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$build/lsan.supp:print_suppressions=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
cd "$build"
ctest --output-on-failure -j "$(nproc)" -L "unit|badinput" "$@"
