# Sourced by the full-disk checks (check-full-disk.sh, check-full-disk-outputs.sh):
#   . "$(dirname "$0")/full-disk-tmpfs.sh" NAME SIZE BUILD_DIR
# Sets BUILD (BUILD_DIR, absolute), ROOT (the source tree, also the working
# directory), tmp (a fresh directory) and mnt (a tmpfs of SIZE at $tmp/disk);
# both are unmounted and removed on exit. Where a tmpfs cannot be mounted
# (mount(2) needs root, not in every container) it says so and exits 77, which
# ctest counts as skipped.
BUILD=$(cd "${3:?usage: $1 BUILD_DIR}" && pwd) || exit 1
cd "$(dirname "${BASH_SOURCE[0]}")/.." || exit 1
ROOT=$PWD
tmp=$(mktemp -d)
mnt=$tmp/disk
mkdir -p "$mnt"
full_disk_cleanup() { mountpoint -q "$mnt" && umount "$mnt"; rm -rf "$tmp"; }
trap full_disk_cleanup EXIT
if ! mount -t tmpfs -o "size=$2" tmpfs "$mnt" 2>/dev/null; then
    echo "$1: cannot mount a tmpfs here (needs root and mount permission): skipped"
    exit 77
fi
