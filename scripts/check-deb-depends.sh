#!/usr/bin/env bash
# Every shared library the packaged binaries need (ELF NEEDED) comes from a
# package the .deb depends on: the Depends list is written by hand
# (cmake/packaging.cmake; dpkg-shlibdeps cannot run for a foreign
# architecture), and a missing entry installs a kiosk that does not start.
# The providing package is looked up among this machine's installed
# libraries of the .deb's architecture (multiarch).
#   scripts/check-deb-depends.sh DEB
set -euo pipefail
DEB=${1:?usage: check-deb-depends.sh DEB}
arch=$(dpkg-deb -f "$DEB" Architecture)
case $arch in
    amd64) triplet=x86_64-linux-gnu ;;
    arm64) triplet=aarch64-linux-gnu ;;
    *) echo "check-deb-depends: architecture $arch not known here"; exit 1 ;;
esac
depends=$(dpkg-deb -f "$DEB" Depends | tr ',' '\n' | sed 's/([^)]*)//; s/^ *//; s/ *$//; s/:.*//')
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
dpkg-deb -x "$DEB" "$tmp"
fail=0
for lib in $(for b in "$tmp"/usr/bin/*; do readelf -d "$b" | sed -n 's/.*NEEDED.*\[\(.*\)\]/\1/p'; done | sort -u); do
    pkg=$(dpkg -S "/usr/lib/$triplet/$lib" "/lib/$triplet/$lib" 2>/dev/null | head -1 | cut -d: -f1 || true)
    if [ -z "$pkg" ]; then
        echo "check-deb-depends: $lib: no installed $arch package provides it here"; fail=1
    elif ! grep -qx "$pkg" <<<"$depends"; then
        echo "check-deb-depends: $lib comes from $pkg, which $(basename "$DEB") does not depend on"; fail=1
    fi
done
[ $fail -eq 0 ] && echo "check-deb-depends: $(basename "$DEB"): every NEEDED library's package is in Depends"
exit $fail
