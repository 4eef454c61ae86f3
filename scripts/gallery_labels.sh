#!/usr/bin/env bash
# The README's label-volume comparison (issue 23): the AAL atlas (Debian
# mricron-data) as one `bodygen exhibit` each, from the left, head up:
#   images/aal_voxel_smooth10.png  voxel-face contours + 10 Taubin steps (the sample until session 9)
#   images/aal_label_smooth.png    contours of each label blurred by 2 voxels (the default now)
# Called by scripts/gallery.sh; runs alone too.
#   scripts/gallery_labels.sh [BUILD_DIR]        (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
bodyview=$build/bin/bodyview
bodygen=$build/bin/bodygen
atlas=/usr/share/mricron/templates/aal.nii.gz
{ [ -x "$bodygen" ] && [ -x "$bodyview" ]; } || { echo "gallery_labels: $build/bin not built" >&2; exit 2; }
[ -f "$atlas" ] || { echo "gallery_labels: $atlas missing (apt install mricron-data)" >&2; exit 2; }
mkdir -p images
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
common=(--groups builder/import/aal_groups.tsv --min-area 3 --view left --jobs "$(nproc)" --quiet)
"$bodygen" exhibit "$atlas" "${common[@]}" --label-smooth 0 --smooth 10 -o "$tmp/voxel_smooth10"
"$bodygen" exhibit "$atlas" "${common[@]}" -o "$tmp/label_smooth"
for name in voxel_smooth10 label_smooth; do
  "$bodyview" --headless --size "${SIZE:-800x500}" --ssaa 2 "$tmp/$name" --screenshot "images/aal_$name.png"
done
echo "gallery: images/aal_voxel_smooth10.png images/aal_label_smooth.png"
