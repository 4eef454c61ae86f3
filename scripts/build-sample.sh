#!/usr/bin/env bash
# Builds the product's sample anatomy: the AAL brain atlas (Debian mricron-data,
# 116 regions) -> contour stack -> one closed mesh per region -> progressive
# meshes -> a kiosk scene grouped by lobe and side (builder/import/aal_groups.tsv)
# -> a kiosk bundle (build/sample/bundle). Regions the pipeline rejects are
# reported and left out of the scene.
# Nothing derived from the atlas is committed; everything lands in build/sample/.
#
#   scripts/build-sample.sh [BODYGEN] [OUT_DIR]
#     BODYGEN  default build/bin/bodygen
#     OUT_DIR  default build/sample
#   JOBS=N     worker threads (default: all cores)
#   SMOOTH=N   Taubin smoothing steps per region (default 10; 0: the raw contour meshes)
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
# --min-area 3: per-slice islands of 1-3 voxels are atlas speckle: dropping them
# gives cleaner models (every region also builds closed without it).
"$BODYGEN" contours "$ATLAS" --labels "$NAMES" --min-area 3 --jobs "$JOBS" -o "$OUT/aal.contours.json"

if ! "$BODYGEN" --help | grep -q '^  build '; then
  echo "build-sample: this bodygen has no 'build' command yet; stopping after contours" >&2
  exit 0
fi
echo "build-sample: meshes, one per region ($JOBS at a time)"
rm -rf "$OUT/regions"
mkdir -p "$OUT/regions"
# One stack per region, so a region the pipeline rejects is reported, not fatal.
python3 - "$OUT" <<'PY'
import json, os, sys
out = sys.argv[1]
stack = json.load(open(os.path.join(out, "aal.contours.json")))
for s in stack["structures"]:
    part = dict(stack, structures=[s])
    part["slices"] = [{"z": sl["z"], "contours": [c for c in sl["contours"] if c["structure"] == s["id"]]}
                      for sl in stack["slices"]]
    # Empty slices inside the region's z range stay: a gap is capped, not bridged.
    kept = [i for i, sl in enumerate(part["slices"]) if sl["contours"]]
    part["slices"] = part["slices"][kept[0]:kept[-1] + 1] if kept else []
    json.dump(part, open(os.path.join(out, "regions", s["id"] + ".contours.json"), "w"))
PY
# --smooth: the atlas is 2 mm voxels; its contours follow voxel edges and the
# slices are 2 mm apart, so unsmoothed regions show stairs and terraces.
SMOOTH=${SMOOTH:-10}
ls "$OUT"/regions/*.contours.json | xargs -P "$JOBS" -I{} sh -c \
  'f={}; "$0" build "$f" -o "${f%.contours.json}.obj" --smooth "$1" --quiet 2> "${f%.contours.json}.err" || true' \
  "$BODYGEN" "$SMOOTH"
failed=0
for err in "$OUT"/regions/*.err; do
  if [ -s "$err" ] && [ ! -f "${err%.err}.obj" ]; then
    echo "build-sample: skipped: $(cat "$err")" >&2
    failed=$((failed + 1))
  fi
  rm -f "$err"
done
rm -f "$OUT"/regions/*.contours.json

# The scene manifest with groups, and the region table.
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

# One hue per lobe group, the right side a shade darker, so the groups read at a glance.
PALETTE = {"frontal": (0.86, 0.45, 0.40), "temporal": (0.42, 0.68, 0.86), "parietal": (0.55, 0.80, 0.45),
           "occipital": (0.92, 0.76, 0.36), "limbic-insula": (0.78, 0.50, 0.82), "central": (0.96, 0.60, 0.30),
           "cerebellum": (0.62, 0.66, 0.78), "other": (0.8, 0.8, 0.8)}

def colour_of(group, side):
    k = 0.82 if side == "right" else 1.0
    return [round(c * k, 3) for c in PALETTE[group]]

stack = json.load(open(os.path.join(out, "aal.contours.json")))
models, groups, rows = [], set(), []
for s in stack["structures"]:
    fname = os.path.join("regions", s["id"] + ".obj")
    if not os.path.exists(os.path.join(out, fname)):
        continue
    name = s["name"]
    group, side = group_of(name), side_of(name)
    gname = group if side == "midline" else "%s-%s" % (group, side)
    groups.add(gname)
    title = (name[:-2] if side != "midline" else name).replace("_", " ")
    if side != "midline":
        title += " (%s)" % side
    # The atlas is in RAS scanner space (z up); the kiosk's up is +Y: turn -90 degrees about X.
    models.append({"name": s["id"], "file": fname, "group": gname, "colour": colour_of(group, side),
                   "transform": {"rotate_deg": [-90, 0, 0]},
                   "label": {"en": {"title": title, "description": "%s, %s" % (group, side)}}})
    rows.append((s["id"], group, side))
scene = {"version": 1, "models": models,
         "camera": {"azimuth_deg": -110, "polar_deg": 72},  # a left-anterior three-quarter view
         "groups": [{"name": g, "visible": True} for g in sorted(groups)],
         "kiosk": {"languages": ["en"]}}
json.dump(scene, open(os.path.join(out, "scene.json"), "w"), indent=1)
with open(os.path.join(out, "regions.tsv"), "w") as f:
    f.write("id\tgroup\tside\n")
    for r in rows:
        f.write("%s\t%s\t%s\n" % r)
print("build-sample: %d of %d regions in %d groups -> %s/scene.json" % (len(models), len(stack["structures"]),
                                                                      len(groups), out))
PY

if "$BODYGEN" --help | grep -q '^  lod '; then
  echo "build-sample: progressive meshes"
  for obj in "$OUT"/regions/*.obj; do
    "$BODYGEN" lod "$obj" -o "${obj%.obj}.bpm" >/dev/null
  done
  sed -i 's/"regions\/\([^"]*\)\.obj"/"regions\/\1.bpm"/' "$OUT/scene.json"
fi
if "$BODYGEN" --help | grep -q '^  pack '; then
  "$BODYGEN" pack "$OUT/scene.json" -o "$OUT/bundle"
  echo "build-sample: done: open it with: bodyview $OUT/bundle"
else
  echo "build-sample: done: $OUT/scene.json"
fi
