#!/usr/bin/env bash
# Packs what bench/gpu_run.sh needs on a GPU machine that has none of this
# project's Debian packages: bodyview and the shared libraries it links (not
# libc, not the GL dispatch libraries: the machine's driver brings those), the
# DejaVu font, the glmark2 bunny, the inputs (the bunny and its 1.1M-triangle
# Loop subdivision as .bpm, the AAL sample, the body scene and its 48-model
# baseline), all in one xz archive that stays under the 64 MiB a run carries.
#
#   bench/gpu_kit.sh [OUT_DIR]   (default gpu-kit; git-ignored)
#   BUILD=DIR  the build to take bodyview and bodygen from (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BUILD=${BUILD:-build}
OUT=${1:-gpu-kit}
STAGE=$(mktemp -d)
trap 'rm -rf "$STAGE"' EXIT
mkdir -p "$OUT" "$STAGE/kit/bin" "$STAGE/kit/lib" "$STAGE/kit/data"
cp "$BUILD/bin/bodyview" "$STAGE/kit/bin/"
ldd "$BUILD/bin/bodyview" | awk '$3 ~ /^\// {print $3}' | while read -r lib; do
  case "$(basename "$lib")" in
    libc.so*|libm.so*|libpthread.so*|libdl.so*|librt.so*|ld-linux*|libEGL.so*|libGLESv2.so*|libGLdispatch.so*|libGL.so*) ;;
    *) cp -L "$lib" "$STAGE/kit/lib/" ;;
  esac
done
cp /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf /usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf "$STAGE/kit/data/"
cp /usr/share/glmark2/models/bunny.obj "$STAGE/kit/data/"
# The progressive meshes (kept between runs: the Loop bunny takes a minute to build).
CACHE="$OUT/cache"
mkdir -p "$CACHE"
[ -f "$CACHE/loop.obj" ] || /usr/bin/python3 bench/loop_bunny.py "$CACHE/loop.obj" 2
"$BUILD/bin/bodygen" lod /usr/share/glmark2/models/bunny.obj -o "$STAGE/kit/data/bunny.bpm" > /dev/null
"$BUILD/bin/bodygen" lod "$CACHE/loop.obj" -o "$STAGE/kit/data/loop.bpm" > /dev/null
# The body scene (its models are the sample's files) and the same triangles as 48 models.
MERGED=48 scripts/build-body-scene.sh "$ROOT/$BUILD/bin/bodygen" "$CACHE/body" > /dev/null
mkdir -p "$STAGE/kit/body/sample" "$STAGE/kit/body/merged"
cp -r "$CACHE/body/sample/bundle" "$STAGE/kit/body/sample/"
cp "$CACHE/body/scene.json" "$STAGE/kit/body/"
cp "$CACHE/body/merged/scene.json" "$STAGE/kit/body/merged/"
cp -r "$CACHE/body/merged/models" "$STAGE/kit/body/merged/" 2>/dev/null || cp "$CACHE/body/merged/"*.bpm "$STAGE/kit/body/merged/"
# Scenes with every model at full detail, for frame times with the LOD controller off.
python3 - "$STAGE/kit/body" <<'PY'
import json, os, sys
root = sys.argv[1]
for rel in ("scene.json", "merged/scene.json"):
    s = json.load(open(os.path.join(root, rel)))
    for m in s["models"]:
        m["lod"] = 1.0
    json.dump(s, open(os.path.join(root, os.path.dirname(rel), "full.json"), "w"))
PY
tar -C "$STAGE" -cJf "$OUT/kit.tar.xz" kit
du -sh "$OUT/kit.tar.xz"
