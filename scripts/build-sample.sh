#!/usr/bin/env bash
# Builds the product's sample anatomy: the AAL brain atlas (Debian mricron-data,
# 116 regions) -> contour stack -> one closed mesh per region -> progressive
# meshes -> a kiosk scene grouped by lobe and side (builder/import/aal_groups.tsv).
# Nothing derived from the atlas is committed; everything lands in build/sample/.
#
#   scripts/build-sample.sh [BODYGEN] [OUT_DIR]
#     BODYGEN  default build/bin/bodygen
#     OUT_DIR  default build/sample
#   JOBS=N     worker threads (default: all cores)
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BODYGEN=${1:-$ROOT/build/bin/bodygen}
OUT=${2:-$ROOT/build/sample}
JOBS=${JOBS:-$(nproc)}
ATLAS=/usr/share/mricron/templates/aal.nii.gz
NAMES=/usr/share/mricron/templates/aal.nii.txt
GROUPS_TABLE=$ROOT/builder/import/aal_groups.tsv

if [ ! -f "$ATLAS" ] || [ ! -f "$NAMES" ]; then
  if [ "$(id -u)" = 0 ]; then
    echo "build-sample: installing mricron-data (the AAL atlas)"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends mricron-data
  else
    echo "build-sample: the AAL atlas is missing; run: sudo apt-get install mricron-data" >&2
    exit 1
  fi
fi
[ -x "$BODYGEN" ] || { echo "build-sample: $BODYGEN not built (cmake --build build)" >&2; exit 1; }
mkdir -p "$OUT"

echo "build-sample: contours ($JOBS jobs)"
"$BODYGEN" contours "$ATLAS" --labels "$NAMES" --jobs "$JOBS" -o "$OUT/aal.contours.json"

if ! "$BODYGEN" --help | grep -q '^  build '; then
  echo "build-sample: this bodygen has no 'build' command yet; stopping after contours" >&2
  exit 0
fi
echo "build-sample: meshes"
"$BODYGEN" build "$OUT/aal.contours.json" -o "$OUT/aal.obj" --json > "$OUT/aal.build.json"

# One OBJ per region, the scene manifest with groups, and the region table.
python3 - "$OUT" "$GROUPS_TABLE" <<'PY'
import fnmatch, json, os, sys
out, table = sys.argv[1], sys.argv[2]
rules = []
for line in open(table):
    line = line.rstrip("\n")
    if not line or line.startswith("#") or line.startswith("pattern\t"):
        continue
    pattern, group = line.split("\t")
    rules.append((pattern, group))

def group_of(name):
    for pattern, group in rules:
        if fnmatch.fnmatchcase(name, pattern):
            return group
    return "other"

def side_of(name):
    return "left" if name.endswith("_L") else "right" if name.endswith("_R") else "midline"

stack = json.load(open(os.path.join(out, "aal.contours.json")))
info = {s["id"]: s for s in stack["structures"]}
os.makedirs(os.path.join(out, "regions"), exist_ok=True)
# Split the multi-object OBJ (global vertex indices) into one file per object.
objects, current, verts = {}, None, []
for line in open(os.path.join(out, "aal.obj")):
    if line.startswith("o "):
        current = line[2:].strip()
        objects[current] = []
    elif line.startswith("v "):
        verts.append(line)
    elif line.startswith("f ") and current is not None:
        objects[current].append([int(t.split("/")[0]) for t in line.split()[1:]])
models, groups, rows = [], set(), []
for name, faces in objects.items():
    used = sorted({i for f in faces for i in f})
    remap = {old: new + 1 for new, old in enumerate(used)}
    sid = name if name in info else next((k for k, v in info.items() if v["name"] == name), name)
    fname = os.path.join("regions", sid + ".obj")
    with open(os.path.join(out, fname), "w") as f:
        f.write("o %s\n" % name)
        for i in used:
            f.write(verts[i - 1])
        for face in faces:
            f.write("f " + " ".join(str(remap[i]) for i in face) + "\n")
    group, side = group_of(info.get(sid, {"name": name})["name"]), side_of(name)
    gname = group if side == "midline" else "%s-%s" % (group, side)
    groups.add(gname)
    title = name[:-2] if side != "midline" else name
    title = title.replace("_", " ") + ("" if side == "midline" else " (%s)" % side)
    colour = info.get(sid, {}).get("color", [0.8, 0.8, 0.8])
    models.append({"name": sid, "file": fname, "group": gname, "colour": colour,
                   "label": {"en": {"title": title, "description": "%s lobe group, %s" % (group, side)}}})
    rows.append((sid, group, side, len(faces)))
scene = {"version": 1, "models": models,
         "groups": [{"name": g, "visible": True} for g in sorted(groups)],
         "kiosk": {"languages": ["en"]}}
json.dump(scene, open(os.path.join(out, "scene.json"), "w"), indent=1)
with open(os.path.join(out, "regions.tsv"), "w") as f:
    f.write("id\tgroup\tside\ttriangles\n")
    for r in rows:
        f.write("%s\t%s\t%s\t%d\n" % r)
print("build-sample: %d regions in %d groups -> %s/scene.json" % (len(models), len(groups), out))
PY

if "$BODYGEN" --help | grep -q '^  lod '; then
  echo "build-sample: progressive meshes"
  for obj in "$OUT"/regions/*.obj; do
    "$BODYGEN" lod "$obj" -o "${obj%.obj}.bpm" >/dev/null
  done
  sed -i 's/"regions\/\([^"]*\)\.obj"/"regions\/\1.bpm"/' "$OUT/scene.json"
fi
echo "build-sample: done: $OUT/scene.json"
