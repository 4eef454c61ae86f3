#!/usr/bin/env bash
# Issue 28: the arm64 .deb installs in an arm64 Debian root under qemu and its
# unit passes `systemd-analyze verify` there (with the root's own arm64
# systemd and the installed /usr/bin/bodyview). Not in CI: the root takes
# ~10 minutes to bootstrap and apt under emulation minutes more.
#   scripts/check-arm64-deb.sh DEB [ROOT]     (ROOT default /work/arm64root)
# Needs debootstrap, qemu-user-static and proot (Debian packages); runs
# without binfmt_misc (proot starts every arm64 program through qemu) and
# without root privileges inside the root (proot -0 fakes them). A ROOT
# already bootstrapped is reused; the package is purged first if present.
set -euo pipefail
DEB=$(readlink -f "${1:?usage: check-arm64-deb.sh DEB [ROOT]}")
cd "$(dirname "$0")/.."
ROOT=${2:-/work/arm64root}
MIRROR=${MIRROR:-http://deb.debian.org/debian}
for tool in debootstrap qemu-aarch64-static proot; do
    command -v "$tool" >/dev/null || { echo "check-arm64-deb: $tool missing (apt install debootstrap qemu-user-static proot)"; exit 77; }
done
[ "$(dpkg-deb -f "$DEB" Architecture)" = arm64 ] || { echo "check-arm64-deb: $DEB is not an arm64 package"; exit 1; }
in_root() {
    proot -0 -q qemu-aarch64-static -r "$ROOT" -b /dev -b /proc -b /sys -b /etc/resolv.conf -w / \
        /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root DEBIAN_FRONTEND=noninteractive "$@"
}
t0=$(date +%s)
if [ ! -x "$ROOT/usr/bin/dpkg" ] || [ -d "$ROOT/debootstrap" ]; then
    echo "--- bootstrapping an arm64 bookworm root in $ROOT"
    [ -d "$ROOT/debootstrap" ] || debootstrap --arch=arm64 --foreign --variant=minbase bookworm "$ROOT" "$MIRROR"
    DEBOOTSTRAP_DIR=/debootstrap proot -0 -q qemu-aarch64-static -r "$ROOT" -b /dev -b /sys -w / \
        /debootstrap/debootstrap --second-stage
fi
echo "--- the root: $(in_root uname -m), $(in_root cat /etc/debian_version)"
cp "$DEB" "$ROOT/tmp/bodygen.deb"
in_root dpkg --purge bodygen >/dev/null 2>&1 || true
# A chroot starts no daemons (policy-rc.d), and systemd's postinst call of
# systemd-tmpfiles with its whole list aborts proot 5.1 (an assertion in its
# path code; each file alone passes): divert it to true for the install.
printf '#!/bin/sh\nexit 101\n' > "$ROOT/usr/sbin/policy-rc.d"
chmod +x "$ROOT/usr/sbin/policy-rc.d"
if ! in_root dpkg-divert --list /usr/bin/systemd-tmpfiles | grep -q local; then
    in_root dpkg-divert --local --rename --add /usr/bin/systemd-tmpfiles
fi
ln -sf /bin/true "$ROOT/usr/bin/systemd-tmpfiles"
echo "--- apt-get install ./bodygen.deb (dependencies from $MIRROR)"
in_root apt-get update -q
# systemd: the package recommends it; with it, the postinst makes the user through systemd-sysusers.
in_root apt-get install -y -q --no-install-recommends systemd /tmp/bodygen.deb
echo "--- checks"
fail=0
status=$(in_root dpkg-query -W -f '${Status} ${Architecture} ${Version}' bodygen)
echo "dpkg: $status"
[[ $status == "install ok installed arm64 "* ]] || { echo "FAIL: not installed"; fail=1; }
in_root getent passwd bodyview || { echo "FAIL: no bodyview user"; fail=1; }
in_root id bodyview || true
in_root /usr/bin/bodygen --version || { echo "FAIL: bodygen does not run"; fail=1; }
# A real run of the arm64 bodygen in the root: a small stack to a mesh.
cp tests/data/stacks/small.contours.json "$ROOT/tmp/small.contours.json" 2>/dev/null \
    && { in_root /usr/bin/bodygen build /tmp/small.contours.json -o /tmp/small.obj --quiet \
         && echo "bodygen build in the root: $(grep -c '^f ' "$ROOT/tmp/small.obj") triangles" \
         || { echo "FAIL: bodygen build in the root"; fail=1; }; }
in_root /usr/bin/bodyview --version || { echo "FAIL: bodyview does not run"; fail=1; }
verify=$(in_root systemd-analyze verify /usr/lib/systemd/system/bodyview.service 2>&1) || { echo "$verify"; echo "FAIL: systemd-analyze verify failed"; fail=1; }
echo "systemd-analyze verify (arm64 systemd $(in_root dpkg-query -W -f '${Version}' systemd)): ${verify:-no complaint}"
[ -z "$verify" ] || { echo "FAIL: systemd-analyze verify complained"; fail=1; }
in_root dpkg --purge bodygen >/dev/null || { echo "FAIL: purge"; fail=1; }
[ ! -e "$ROOT/usr/bin/bodyview" ] || { echo "FAIL: purge left /usr/bin/bodyview"; fail=1; }
echo "check-arm64-deb: $([ $fail -eq 0 ] && echo passed || echo FAILED) in $(( $(date +%s) - t0 )) s"
exit $fail
