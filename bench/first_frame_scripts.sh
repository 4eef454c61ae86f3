#!/usr/bin/env bash
# The kiosk's first frame with text in every script (issue 27): the AAL bundle
# as built (English) against a copy whose first frame needs every fallback font
# (Arabic UI, mirrored; group buttons in Latin, Cyrillic, Greek, Arabic, Hebrew,
# Chinese, Japanese), and optionally a BASE binary (the code before shaping) on
# the English bundle. Runs alternate, so all figures come from the same run.
#
#   bench/first_frame_scripts.sh [BUNDLE/]   (default build/sample/bundle/)
#   BODYVIEW=bin   the binary under test (default build/bin/bodyview)
#   BASE=bin       the binary to compare with (optional)
#   RUNS=N         runs per case (default 7); medians and ranges are printed
#   SHOT=PNG       also writes the every-script first frame as a PNG
set -euo pipefail
cd "$(dirname "$0")/.."
BODYVIEW=${BODYVIEW:-build/bin/bodyview}
RUNS=${RUNS:-7}
BUNDLE=$(realpath "${1:-build/sample/bundle/}")
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
ln -s "$BUNDLE/models" "$TMP/models"
python3 - "$BUNDLE/scene.json" "$TMP/scene.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
names = ["frontal", "лобная", "μετωπιαίος", "الجبهي", "מצחית", "额叶", "前頭葉", "temporal", "височная", "κροταφικός",
         "الصدغي", "רקתית", "颞叶", "側頭葉", "小脳"]
rename = {g["name"]: f"{names[i % len(names)]} {i}" for i, g in enumerate(scene["groups"])}
for g in scene["groups"]:
    g["name"] = rename[g["name"]]
for m in scene["models"]:
    if m.get("group") in rename:
        m["group"] = rename[m["group"]]
scene["kiosk"]["languages"] = ["ar", "en"]
json.dump(scene, open(sys.argv[2], "w"), ensure_ascii=False)
PY
first_frame() {  # BIN SCENE -> ms
  "$1" --headless --frames 2 --kiosk-stats --scene "$2" 2>&1 | sed -n 's/.*first frame \([0-9.]*\) ms.*/\1/p'
}
declare -A times
cases=("new-en" "new-every-script")
[ -n "${BASE:-}" ] && cases=("base-en" "${cases[@]}")
for _ in $(seq "$RUNS"); do
  for c in "${cases[@]}"; do
    case $c in
      base-en) t=$(first_frame "$BASE" "$BUNDLE/scene.json") ;;
      new-en) t=$(first_frame "$BODYVIEW" "$BUNDLE/scene.json") ;;
      new-every-script) t=$(first_frame "$BODYVIEW" "$TMP/scene.json") ;;
    esac
    times[$c]="${times[$c]:-} $t"
  done
done
ref=${cases[0]}
median() { tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
m_ref=$(echo "${times[$ref]}" | median)
for c in "${cases[@]}"; do
  m=$(echo "${times[$c]}" | median)
  range=$(echo "${times[$c]}" | tr ' ' '\n' | grep . | sort -g | sed -n '1p;$p' | paste -sd-)
  printf '%-18s first frame median %6.1f ms (range %s ms), ratio to %s %.2f\n' "$c" "$m" "$range" "$ref" \
    "$(echo "$m / $m_ref" | bc -l)"
done
if [ -n "${SHOT:-}" ]; then
  printf 'size 1280 800\n0.5 end\n' > "$TMP/idle.replay"
  "$BODYVIEW" --headless --size 1280x800 --scene "$TMP/scene.json" --replay "$TMP/idle.replay" --screenshot "$SHOT"
fi
