#!/usr/bin/env bash
# The fresh-machine check: builds a minimal Debian 12 root (only apt, git, ca-certificates and
# sudo, made by mmdebstrap), clones this repository's committed HEAD into it, and runs the
# README's two commands there, as root, printing what each took:
#   scripts/render.sh   installs what is missing, builds, renders the default scene
#   scripts/test.sh     installs what is missing, builds and runs every test
# A machine that has been used for development keeps every package ever installed by hand, so a
# green CI there can hide a missing install step; this root has none of them.
#
#   scripts/fresh-machine.sh [--render-only] [--keep] [-- TEST_ARGS...]
#     --render-only   run only scripts/render.sh
#     --keep          keep the root afterwards (its path is printed) instead of removing it
#     TEST_ARGS       go to scripts/test.sh (then to ctest), e.g. -- -L unit
# Environment: CLPT_DEBIAN_MIRROR (default: the first deb.debian.org-style URI of this machine's
# apt sources, else http://deb.debian.org/debian), CLPT_FRESH_DIR (where the root is made;
# default a new directory under ${TMPDIR:-/tmp}).
#
# Needs root (chroot, mounts) and the Debian mirror. Where either is missing it says so and exits
# 2 before touching anything. Installs mmdebstrap on this machine if it is missing. Exit status:
# 0 when both commands succeed in the root, 1 when one fails, 2 for a missing prerequisite.
set -euo pipefail

CLPT_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
SUITE=bookworm

log() { printf 'fresh-machine: %s\n' "$*" >&2; }
die() { log "$1"; exit "${2:-1}"; }

render_only=0 keep=0 test_args=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --render-only) render_only=1 ;;
    --keep) keep=1 ;;
    --) shift; test_args=("$@"); break ;;
    -h|--help) sed -n '2,21p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown argument '$1' (see --help)" 2 ;;
  esac
  shift
done

# --- Prerequisites, checked before anything is touched ----------------------------------------
[[ $(id -u) -eq 0 ]] || die "needs root (it makes a chroot and mounts /proc, /sys and /dev into it); run it as root" 2
command -v git >/dev/null || die "needs git to clone the repository into the root" 2
git -C "$CLPT_ROOT" rev-parse --verify -q HEAD >/dev/null || die "$CLPT_ROOT has no commit to clone" 2

mirror=${CLPT_DEBIAN_MIRROR:-}
if [[ -z "$mirror" ]]; then
  mirror=$(grep -hoE '^(URIs:|deb)[[:space:]]+[^[:space:]]+' /etc/apt/sources.list.d/*.sources \
             /etc/apt/sources.list 2>/dev/null | awk '{print $2}' | grep -v -- '-security' | head -n 1 || true)
  mirror=${mirror:-http://deb.debian.org/debian}
fi
probe=$(mktemp)
if ! /usr/lib/apt/apt-helper download-file "$mirror/dists/$SUITE/Release" "$probe" >/dev/null 2>&1; then
  rm -f "$probe"
  die "the Debian mirror $mirror does not answer (fetching dists/$SUITE/Release failed); set CLPT_DEBIAN_MIRROR to one that does" 2
fi
rm -f "$probe"

if ! command -v mmdebstrap >/dev/null; then
  log "installing mmdebstrap on this machine"
  apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends mmdebstrap >/dev/null
fi

# --- The root ------------------------------------------------------------------------------------
root=${CLPT_FRESH_DIR:-$(mktemp -d "${TMPDIR:-/tmp}/clpt-fresh.XXXXXX")}
mounted=()
cleanup() {
  local m
  for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount -l "${mounted[i]}" 2>/dev/null || true; done
  if [[ $keep -eq 1 ]]; then log "kept the root at $root"; else rm -rf --one-file-system "$root"; fi
}
trap cleanup EXIT

seconds() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(seconds)" 'BEGIN { printf "%.0f s", b - a }'; }

t=$(seconds)
rmdir "$root" 2>/dev/null || true  # mmdebstrap wants to create it (or find it empty)
mmdebstrap --quiet --variant=apt --include=git,ca-certificates,sudo "$SUITE" "$root" "$mirror"
log "minimal Debian $SUITE root made in $(elapsed "$t"): $root"

git clone -q "$CLPT_ROOT" "$root/root/clpt"
log "cloned $(git -C "$CLPT_ROOT" rev-parse --short HEAD) into /root/clpt"
cp /etc/resolv.conf "$root/etc/resolv.conf" 2>/dev/null || true
for m in proc sys dev; do
  mount --rbind "/$m" "$root/$m"
  mounted+=("$root/$m")
done

# Runs a README command in the root with a clean environment (as CI does: CI=true, no stdin).
in_root() {
  chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    LANG=C.UTF-8 CI=true bash -c 'cd /root/clpt && "$@"' bash "$@" </dev/null
}

status=0
t=$(seconds)
if in_root bash scripts/render.sh; then
  log "scripts/render.sh: passed in $(elapsed "$t")"
else
  log "scripts/render.sh: FAILED after $(elapsed "$t")"
  status=1
fi
if [[ $render_only -eq 0 && $status -eq 0 ]]; then
  t=$(seconds)
  if in_root bash scripts/test.sh "${test_args[@]}"; then
    log "scripts/test.sh: passed in $(elapsed "$t")"
  else
    log "scripts/test.sh: FAILED after $(elapsed "$t")"
    status=1
  fi
fi
exit $status
