#!/usr/bin/env bash
# Builds a body-scale test scene from packaged data with the project's own
# binaries: COPIES copies of the AAL sample (scripts/build-sample.sh: 116
# regions of Debian's mricron-data atlas) side by side in a grid, one model per
# region and copy (18 copies: 2,088 models, ~4.5 M triangles at full detail).
# With MERGED=N it also writes the same triangles as N models (the copies'
# regions, placed, merged into N OBJ objects and made progressive by `bodygen
# lod`): the baseline a many-model scene's frame time is compared against.
#
#   scripts/build-body-scene.sh [BODYGEN] [OUT_DIR]
#     BODYGEN  default build/bin/bodygen
#     OUT_DIR  default build/body-scene
#   COPIES=N   copies of the atlas (default 18)
#   MERGED=N   also OUT_DIR/merged/scene.json with N models (default 0: none)
#   SAMPLE=DIR an existing sample, as build-sample.sh makes it (DIR/bundle; default:
#              OUT_DIR/sample, built when missing)
#
# Output: OUT_DIR/scene.json (the copies; model files stay in the sample) and,
# with MERGED, OUT_DIR/merged/scene.json. Nothing here is committed.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BODYGEN=${1:-$ROOT/build/bin/bodygen}
OUT=${2:-$ROOT/build/body-scene}
COPIES=${COPIES:-18}
MERGED=${MERGED:-0}
SAMPLE=${SAMPLE:-$OUT/sample}
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)

if [ ! -f "$SAMPLE/bundle/scene.json" ]; then
  echo "build-body-scene: building the AAL sample in $SAMPLE"
  "$ROOT/scripts/build-sample.sh" "$BODYGEN" "$SAMPLE"
fi
SAMPLE=$(cd "$SAMPLE/bundle" && pwd)
# Full-detail OBJs of the sample's models: the grid's extent and the merged baseline read them.
mkdir -p "$OUT/obj"
for f in "$SAMPLE"/models/*.bpm; do
  obj="$OUT/obj/$(basename "${f%.bpm}").obj"
  [ -f "$obj" ] || "$BODYGEN" extract "$f" --ratio 1 -o "$obj" >/dev/null
done

python3 - "$SAMPLE" "$OUT" "$COPIES" "$MERGED" "$OUT/obj" <<'PY'
import json, math, os, sys
sample, out, copies, merged, objdir = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]), sys.argv[5]
base = json.load(open(os.path.join(sample, "scene.json")))

def rotate(p, deg):
    # translate * Rz * Ry * Rx * scale (SCENE.md): X first.
    x, y, z = p
    for axis, a in ((0, deg[0]), (1, deg[1]), (2, deg[2])):
        c, s = math.cos(math.radians(a)), math.sin(math.radians(a))
        if axis == 0: y, z = y * c - z * s, y * s + z * c
        elif axis == 1: x, z = x * c + z * s, -x * s + z * c
        else: x, y = x * c - y * s, x * s + y * c
    return x, y, z

def read_obj(path):
    vs, fs = [], []
    for line in open(path):
        if line.startswith("v "):
            vs.append(tuple(float(t) for t in line.split()[1:4]))
        elif line.startswith("f "):
            fs.append(tuple(int(t.split("/")[0]) for t in line.split()[1:4]))
    return vs, fs

# The sample's extent (its OBJs, placed by their transforms) sets the grid spacing.
lo, hi = [1e30] * 3, [-1e30] * 3
meshes = {}
for m in base["models"]:
    obj = os.path.join(objdir, os.path.splitext(os.path.basename(m["file"]))[0] + ".obj")
    vs, fs = read_obj(obj)
    deg = m.get("transform", {}).get("rotate_deg", [0, 0, 0])
    vs = [rotate(v, deg) for v in vs]
    meshes[m["name"]] = (vs, fs)
    for v in vs:
        lo = [min(a, b) for a, b in zip(lo, v)]
        hi = [max(a, b) for a, b in zip(hi, v)]
step = 1.1 * max(hi[0] - lo[0], hi[1] - lo[1])
columns = math.ceil(math.sqrt(copies * 2))
models, triangles = [], 0
placed = []  # (name, translate)
for c in range(copies):
    t = [(c % columns) * step, -(c // columns) * step, 0.0]
    for m in base["models"]:
        mm = json.loads(json.dumps(m))
        mm["name"] = "%s_%02d" % (m["name"], c)
        mm["file"] = os.path.relpath(os.path.join(sample, m["file"]), out)
        mm.setdefault("transform", {})["translate"] = t
        models.append(mm)
        placed.append((m["name"], t))
        triangles += len(meshes[m["name"]][1])
scene = dict(base, models=models)
json.dump(scene, open(os.path.join(out, "scene.json"), "w"), indent=1)
print("build-body-scene: %d models, %d triangles at full detail -> %s/scene.json" % (len(models), triangles, out))

if merged > 0:
    # The same placed triangles as `merged` models of about equal size: one OBJ object each.
    mdir = os.path.join(out, "merged")
    os.makedirs(mdir, exist_ok=True)
    per = math.ceil(len(placed) / merged)
    mmodels = []
    for k in range(0, len(placed), per):
        name = "part%02d" % (k // per)
        with open(os.path.join(mdir, name + ".obj"), "w") as f:
            f.write("o %s\n" % name)
            offset = 0
            for region, t in placed[k:k + per]:
                vs, fs = meshes[region]
                f.writelines("v %.5f %.5f %.5f\n" % (v[0] + t[0], v[1] + t[1], v[2] + t[2]) for v in vs)
                f.writelines("f %d %d %d\n" % (a + offset, b + offset, c + offset) for a, b, c in fs)
                offset += len(vs)
        mmodels.append({"name": name, "file": name + ".bpm", "colour": [0.8, 0.6, 0.5],
                        "label": {"en": {"title": name, "description": "merged regions"}}})
    json.dump(dict(base, models=mmodels, groups=[]), open(os.path.join(mdir, "scene.json"), "w"), indent=1)
    print("build-body-scene: the same triangles as %d models -> %s/scene.json" % (len(mmodels), mdir))
PY

if [ "$MERGED" -gt 0 ]; then
  ls "$OUT"/merged/*.obj | xargs -P "$(nproc)" -I{} sh -c 'f={}; "$0" lod "$f" -o "${f%.obj}.bpm" --jobs 1 >/dev/null' \
    "$BODYGEN"
  rm -f "$OUT"/merged/*.obj
fi
