#!/usr/bin/env bash
# `clpt verify --device oclgrind`: Oclgrind (a simulator of an OpenCL device, Debian `oclgrind`)
# must pass against the PoCL reference. Both drivers are exposed to the test's processes only,
# through the oclgrind tier's vendors directory (OCL_ICD_VENDORS, set by ctest; run by hand
# without it, the script makes one in its work directory). Oclgrind runs a few hundred
# paths/s, so the images are tiny (16x12, 16 spp: 3072 paths a render) and the matrix a subset:
# the glass scene (lambertian, emitter and dielectric) x both forms x robust and double, 4 rows, 52 s on the 2
# shared cores at load 8 (2 scenes x 2 forms x 2 precisions took 74-114 s). Statistical power at
# this size is low (a 2% shift would reach z ~0.2): this checks that a second driver builds, runs
# and agrees, not the tests' sensitivity, which verify_cli.sh checks on PoCL.
# Fails, naming the Debian package, when Oclgrind is not installed (scripts/test.sh installs it).
#   verify_oclgrind.sh CLPT SOURCE_DIR WORK_DIR
set -u
clpt=$1 src=$2 work=$3
oclgrind_icd=/usr/lib/oclgrind/liboclgrind-rt-icd.so
pocl_icd=/etc/OpenCL/vendors/pocl.icd
if [[ ! -f $oclgrind_icd || ! -f $pocl_icd ]]; then
  echo "FAIL: needs $oclgrind_icd (Debian package oclgrind) and $pocl_icd (pocl-opencl-icd)"
  exit 1
fi
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
if [[ -z ${OCL_ICD_VENDORS:-} ]]; then
  mkdir vendors && cp "$pocl_icd" vendors/pocl.icd && echo "$oclgrind_icd" >vendors/oclgrind.icd || exit 1
  export OCL_ICD_VENDORS="$work/vendors"
fi
export CLPT_CACHE_DIR="$work/cache"
unset CLPT_INJECT_FAULT POCL_DEVICES
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$clpt" devices >devices.out 2>&1
grep -q "Oclgrind Simulator" devices.out && grep -q "Portable Computing Language" devices.out ||
  { fail "the vendors directory does not expose both Oclgrind and PoCL"; cat devices.out; }

"$clpt" verify --device oclgrind --scenes glass --forms megakernel,wavefront --precisions robust,double \
  --width 16 --height 12 --spp 16 --json oclgrind.json >verify.out 2>verify.err
status=$?
[[ $status -eq 0 ]] || { fail "verify --device oclgrind exited $status, expected 0"; cat verify.out verify.err; }
grep -q "^verify: 4 of 4 rows passed$" verify.out || { fail "not 4 of 4 rows passed"; cat verify.out; }
python3 - oclgrind.json <<'PY' || fail "JSON"
import json, sys
doc = json.load(open(sys.argv[1]))
assert doc["reference_mode"] == "device" and "Portable Computing Language" in doc["reference"], doc
assert doc["total"] == 4 and doc["passed"] == 4, doc
for r in doc["rows"]:
    assert "Oclgrind" in r["device"] and not r["is_reference_device"], r
    assert r["verdict"] == "PASS" and r["paths_per_s"] > 0, r
PY

if [[ $failures -gt 0 ]]; then echo "$failures failure(s)"; exit 1; fi
echo "Oclgrind passes verify against PoCL"
