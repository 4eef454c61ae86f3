#!/usr/bin/env bash
# Checks the packaged service files (packaging/): the unit passes
# `systemd-analyze verify` without a single complaint (ExecStart pointed at the
# built bodyview), keeps the appliance settings the kiosk relies on, and the
# sysusers.d file creates the user and its groups in an empty root.
#   scripts/check-service.sh BUILD_DIR      exit 77 (skipped) without systemd-analyze
set -euo pipefail
BUILD=$(cd "${1:?usage: check-service.sh BUILD_DIR}" && pwd)
cd "$(dirname "$0")/.."
UNIT=packaging/systemd/bodyview.service
command -v systemd-analyze >/dev/null || { echo "check-service: systemd-analyze not installed (package systemd): skipped"; exit 77; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed "s#^ExecStart=/usr/bin/bodyview#ExecStart=$BUILD/bin/bodyview#" "$UNIT" > "$tmp/bodyview.service"
[ -x "$BUILD/bin/bodyview" ] || { echo "check-service: $BUILD/bin/bodyview not built"; exit 1; }
out=$(systemd-analyze verify "$tmp/bodyview.service" 2>&1) || { echo "$out"; echo "check-service: verify failed"; exit 1; }
[ -z "$out" ] || { echo "$out"; echo "check-service: verify complained"; exit 1; }
for want in '^Type=notify$' '^Restart=always$' '^WatchdogSec=' '^ProtectSystem=strict$' '^NoNewPrivileges=yes$' \
            '^User=bodyview$' '^CacheDirectory=bodyview$' \
            '^Environment=MESA_SHADER_CACHE_DIR=/var/cache/bodyview$' '^ExecStart=/usr/bin/bodyview --config /etc/bodyview/bodyview.conf$'; do
    grep -q "$want" "$UNIT" || { echo "check-service: $UNIT lacks $want"; exit 1; }
done
if command -v systemd-sysusers >/dev/null; then
    mkdir -p "$tmp/root/etc"
    systemd-sysusers --root="$tmp/root" "$PWD/packaging/systemd/bodyview.sysusers" >/dev/null 2>&1
    grep -q '^bodyview:x:[0-9]*:[0-9]*:.*:/usr/sbin/nologin$' "$tmp/root/etc/passwd" || { echo "check-service: no bodyview user"; exit 1; }
    for g in video input render; do
        grep -q "^$g:x:[0-9]*:bodyview\$" "$tmp/root/etc/group" || { echo "check-service: bodyview not in $g"; exit 1; }
    done
fi
echo "check-service: $UNIT verified, sysusers.d creates bodyview in video, input, render"
