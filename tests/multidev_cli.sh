#!/usr/bin/env bash
# `clpt render --device` over several devices, end to end (run with POCL_DEVICES="pthread
# pthread", two identical PoCL devices):
#  * device 1 failing at its 2nd launch (CLPT_INJECT_FAULT=launch:1:2): exit 0, the failure printed
#    once with the CL error and the device, the full spp, and an image that `clpt compare` finds
#    equal in distribution to a plain render of another seed (test_multi_device.cpp checks that
#    it equals the same seed's film exactly);
#  * device 1 failing its build: the render completes on device 0, the image of that seed;
#  * every device failing: exit 4, both errors printed, no output file;
#  * --device 0,0 / 7 / all, : usage errors (exit 2) naming --device and the entry;
#  * --explain prints the render plan once per selected device, after selection, with each
#    device's own form and loop (device 1 asked for the wavefront's path pool by --form), and
#    each device's vector width measured from PoCL's vectoriser remarks (both devices are PoCL's).
#   multidev_cli.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
export CLPT_CACHE_DIR="$work/cache"
unset CLPT_INJECT_FAULT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

render() {  # render OUTPUT SEED ARGS...: stdout in OUTPUT.out, stderr in OUTPUT.err, returns the exit code
  local out=$1 seed=$2
  shift 2
  "$clpt" render "$src/scenes/diffuse.toml" --width 64 --height 48 --spp 64 --sampler jitter \
    --seed "$seed" -o "$out" "$@" >"$out.out" 2>"$out.err"
}
expect_exit() {  # expect_exit CODE WHAT OUTPUT
  local status=$1 code=$2 what=$3 out=$4
  if [[ $status -ne $code ]]; then fail "$what exited $status, expected $code"; cat "$out.out" "$out.err"; fi
}
count() { grep -c -- "$1" "$2"; }

render plain.exr 1 --device 0
expect_exit $? 0 "plain render on device 0" plain.exr

# The plan: one block per device of the list, each resolved for its device.
render explain.exr 1 --device 0,1 --explain
expect_exit $? 0 "render --explain on two devices" explain.exr
[[ $(count "^render plan: 64x48, 64 spp" explain.exr.out) -eq 1 ]] || { fail "no render plan line"; cat explain.exr.out; }
[[ $(count "^device [01]: device '" explain.exr.out) -eq 2 ]] || { fail "not one plan block per device"; cat explain.exr.out; }
[[ $(count "megakernel loop: lockstep, work-groups of 64" explain.exr.out) -eq 2 ]] ||
  { fail "the CPU devices' resolved lockstep loop is not printed"; cat explain.exr.out; }
# PoCL vectorises the lockstep loop across work-items: a measured width of 2 or more per device
# ("work-items", plural; one is "1 work-item").
[[ $(count "^    vector width: [1-9][0-9]* work-items (vectorised loops: " explain.exr.out) -eq 2 ]] ||
  { fail "not one measured vector width per device"; cat explain.exr.out explain.exr.err; }
render explain_wf.exr 1 --device 1 --form wavefront --paths-in-flight 4096 --explain
expect_exit $? 0 "render --explain --form wavefront" explain_wf.exr
grep -q "execution form: wavefront (--form)" explain_wf.exr.out && grep -q "path pool: 4096 paths in flight" explain_wf.exr.out ||
  { fail "the wavefront plan is not printed"; cat explain_wf.exr.out; }
grep -q "^    vector width: [1-9][0-9]* work-item" explain_wf.exr.out ||
  { fail "the wavefront plan has no measured vector width"; cat explain_wf.exr.out explain_wf.exr.err; }

# A launch failing mid-render: the work goes to the other device. Launches of about 1 ms, so that
# each device has many (the whole render takes a few tens of ms on PoCL).
CLPT_INJECT_FAULT=launch:1:2 render launch_fault.exr 2 --device all --launch-ms 1
expect_exit $? 0 "render with launch:1:2" launch_fault.exr
notice="device 1 (device '.*) failed: clEnqueueNDRangeKernel failed with CL_OUT_OF_RESOURCES on device .*; its work goes to the other devices"
[[ $(count "$notice" launch_fault.exr.err) -eq 1 ]] || { fail "launch failure not printed exactly once"; cat launch_fault.exr.err; }
grep -q "64x48, 64 spp" launch_fault.exr.out || { fail "launch fault: not the full 64 spp"; cat launch_fault.exr.out; }
[[ -f launch_fault.exr ]] || fail "launch fault: no output"
"$clpt" compare plain.exr launch_fault.exr >compare.out || { fail "launch fault: clpt compare against another seed failed"; cat compare.out; }

# A build failing: the render completes on the other device.
CLPT_INJECT_FAULT=build:1 render build_fault.exr 1 --device 0,1
expect_exit $? 0 "render with build:1" build_fault.exr
[[ $(count "device 1 (device '.*) failed: clBuildProgram failed with" build_fault.exr.err) -eq 1 ]] ||
  { fail "build failure not printed once"; cat build_fault.exr.err; }
grep -q "64x48, 64 spp" build_fault.exr.out || fail "build fault: not the full 64 spp"
"$clpt" compare --same-seed plain.exr build_fault.exr >same2.out || { fail "build fault: not the image of one device"; cat same2.out; }

# Every device failing: exit 4 with both errors, nothing written.
CLPT_INJECT_FAULT=launch:0:1,launch:1:1 render all_fail.exr 1 --device all
expect_exit $? 4 "render with every device failing" all_fail.exr
grep -q "every device failed" all_fail.exr.err || { fail "all failing: no message"; cat all_fail.exr.err; }
[[ $(count "^  device [01] (device .*CL_OUT_OF_RESOURCES" all_fail.exr.err) -eq 2 ]] || { fail "all failing: not both errors"; cat all_fail.exr.err; }
[[ -e all_fail.exr || -e all_fail.png ]] && fail "all failing: an output file was written"

# Bad --device lists.
for case in "0,0|--device '0,0': entry '0' names device 0 a second time" \
            "7|--device '7': no such device" \
            "all,|--device 'all,': empty entry"; do
  spec=${case%%|*} message=${case#*|}
  render bad.exr 1 --device "$spec"
  expect_exit $? 2 "--device $spec" bad.exr
  grep -qF -- "$message" bad.exr.err || { fail "--device $spec: expected '$message'"; cat bad.exr.err; }
  grep -q "available:" bad.exr.err || fail "--device $spec: devices not listed"
  [[ -e bad.exr ]] && fail "--device $spec: an output file was written"
done

if [[ $failures -gt 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "all multi-device CLI checks passed"
