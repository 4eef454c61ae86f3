#!/usr/bin/env bash
# Regenerates the README gallery in images/: the Stanford bunny (Debian
# glmark2-data) in every style, a LOD strip (100/40/10/2% of the triangles, from
# a progressive mesh when bodygen is built, else bodyview's OBJ preview LOD) and
# a mixed-style scene with a selection. Renders headless (Mesa llvmpipe works),
# 640x400 (the strip 1280x400) with 2x supersampling.
#   scripts/gallery.sh [BUILD_DIR]        (default: build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
bodyview=$build/bin/bodyview
bodygen=$build/bin/bodygen
bunny=${BUNNY:-/usr/share/glmark2/models/bunny.obj}
out=images
[ -x "$bodyview" ] || { echo "gallery: $bodyview not built" >&2; exit 2; }
[ -f "$bunny" ] || { echo "gallery: $bunny missing (apt install glmark2-data)" >&2; exit 2; }
mkdir -p "$out"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
shot() { "$bodyview" --headless --size "${SIZE:-640x400}" --ssaa 2 --view 20,80 "$@"; }

# 1. The same model in every style.
for style in smooth wireframe lines hatching hatching-2tone; do
  lod=1
  [ "$style" = wireframe ] && lod=0.1  # at full density the wire would be solid ink
  shot --model "$bunny" --style "$style" --lod "$lod" --line-width 2.5 --screenshot "$out/style_$style.png"
  echo "gallery: $out/style_$style.png"
done

# 2. LOD strip: progressive mesh levels (fallback: OBJ preview simplification).
model=$bunny
if [ -x "$bodygen" ] && "$bodygen" lod "$bunny" -o "$tmp/bunny.bpm" >/dev/null &&
  SIZE=64x40 shot --model "$tmp/bunny.bpm" --lod 0.1 --screenshot "$tmp/check.png"; then
  model=$tmp/bunny.bpm
else
  echo "gallery: no usable progressive mesh; the LOD strip uses the OBJ preview LOD" >&2
fi
# One scene of four copies side by side, each at its own fixed LOD.
cat > "$tmp/lod.json" <<JSON
{
  "version": 1,
  "models": [
    {"name": "lod100", "file": "$model", "transform": {"translate": [-3.3, 0, 0]}, "lod": 1.0},
    {"name": "lod40", "file": "$model", "transform": {"translate": [-1.1, 0, 0]}, "lod": 0.4},
    {"name": "lod10", "file": "$model", "transform": {"translate": [1.1, 0, 0]}, "lod": 0.1},
    {"name": "lod2", "file": "$model", "transform": {"translate": [3.3, 0, 0]}, "lod": 0.02}
  ],
  "camera": {"azimuth_deg": 0, "polar_deg": 85, "fov_deg": 30}
}
JSON
SIZE=1280x400 shot --scene "$tmp/lod.json" --style wireframe --line-width 1.2 --screenshot "$out/lod_strip.png"
echo "gallery: $out/lod_strip.png (100/40/10/2% of $(basename "$model"))"

# 3. A mixed-style scene: the textbook idea of a detailed structure inside a sketched body.
cat > "$tmp/scene.json" <<JSON
{
  "version": 1,
  "models": [
    {"name": "sketch", "file": "$model", "colour": [0.9, 0.88, 0.82], "style": "lines",
     "transform": {"translate": [-2.1, 0, 0], "scale": 1.0}, "lod": 0.4},
    {"name": "study", "file": "$model", "colour": [0.85, 0.45, 0.40], "style": "smooth",
     "transform": {"translate": [0, 0, 0], "scale": 1.0}},
    {"name": "shaded", "file": "$model", "colour": [0.95, 0.92, 0.85], "style": "hatching",
     "transform": {"translate": [2.1, 0, 0], "scale": 1.0}},
    {"name": "small", "file": "$model", "colour": [0.4, 0.6, 0.9], "style": "hatching-2tone",
     "transform": {"translate": [0.3, -0.65, 1.3], "scale": 0.35}}
  ],
  "camera": {"azimuth_deg": 15, "polar_deg": 80, "fov_deg": 35}
}
JSON
shot --scene "$tmp/scene.json" --screenshot "$out/mixed_scene.png"
shot --scene "$tmp/scene.json" --select study --xray --screenshot "$out/selection_xray.png"
echo "gallery: $out/mixed_scene.png $out/selection_xray.png"

# 4. Exhibits made by one `bodygen exhibit` command each (Debian mricron-data atlases),
# shown from their home camera: the sample (AAL, scripts/build-sample.sh) and JHU white matter.
atlases=/usr/share/mricron/templates
if [ -x "$bodygen" ] && [ -f "$atlases/aal.nii.gz" ] && [ -f "$atlases/JHU-WhiteMatter-labels-1mm.nii.gz" ]; then
  "$bodygen" exhibit "$atlases/aal.nii.gz" --groups builder/import/aal_groups.tsv --min-area 3 \
    --view left --jobs "$(nproc)" --quiet -o "$tmp/aal"
  "$bodygen" exhibit "$atlases/JHU-WhiteMatter-labels-1mm.nii.gz" --min-area 3 --smooth 10 --view left \
    --jobs "$(nproc)" --quiet -o "$tmp/jhu"
  for name in aal jhu; do
    "$bodyview" --headless --size "${SIZE:-640x400}" --ssaa 2 "$tmp/$name" --screenshot "$out/exhibit_$name.png"
  done
  echo "gallery: $out/exhibit_aal.png $out/exhibit_jhu.png"
  # 5. The AAL atlas from voxel-face contours smoothed by --smooth 10 and from blurred labels.
  scripts/gallery_labels.sh "$build"
else
  echo "gallery: no bodygen or mricron-data: exhibit pictures skipped" >&2
fi
