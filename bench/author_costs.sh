#!/usr/bin/env bash
# The authoring window's costs on a bundle, this build against one without this change:
#   edits         `bodyview --author BUNDLE/ --kiosk-stats` replays a typed .bpm path in the
#                 add-model field and Enter, then Delete (the new model is selected): the
#                 window prints how long loading every model took at start, and per edit how
#                 long applying it took, how, and the frame that drew it (the frame whose input
#                 held the edit: no frame passes between edit and picture). Before this change
#                 an add or remove reloaded every model, i.e. cost the start's load.
#   first frame   `bodyview BUNDLE/ --headless --frames 1 --kiosk-stats`, BASE and NEW
#                 alternating: the kiosk's first frame must not change with the author code.
# usage: bench/author_costs.sh BASE_BODYVIEW NEW_BODYVIEW BUNDLE/ [RUNS=5]
# The add-model row is found from the bundle's groups (rows 3.. are the closed groups, then
# "(no group)" when a model has none, then the field; kiosk/author/panel.cpp at 1280x800).
set -euo pipefail
base=$1 new=$2 bundle=${3%/} runs=${4:-5}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
row=$(python3 -c "
import json, sys
s = json.load(open('$bundle/scene.json'))
loose = any(not m.get('group') for m in s['models'])
print(3 + len(s.get('groups', [])) + (1 if loose else 0))")
y=$((row * 26 + 13))
extra="$work/extra.bpm"
cp "$(python3 -c "import json; s=json.load(open('$bundle/scene.json')); print('$bundle/' + s['models'][0]['file'])")" "$extra"
{
  echo "size 1280 800"
  echo "0.1 mouse-down left 284 $y"
  echo "0.12 mouse-up left 284 $y"
  python3 -c "print('\n'.join('0.2 text %d' % ord(c) for c in '$extra'))"
  echo "0.3 key 265"
  echo "0.4 key 258"
  echo "0.5 end"
} > "$work/edits.replay"
: > "$work/results"
for i in $(seq "$runs"); do
  "$new" --author "$bundle/" --headless --size 1280x800 --replay "$work/edits.replay" --kiosk-stats 2>&1 |
    grep 'bodyview: author:' | grep -v unsaved >> "$work/edits" || true
  for build in base new; do
    bin=$base; [ "$build" = new ] && bin=$new
    ms=$("$bin" "$bundle/" --headless --size 1280x800 --frames 1 --kiosk-stats 2>&1 | grep -o 'first frame [0-9.]* ms' | grep -o '[0-9.]*' | head -1 || true)
    echo "$build ${ms:-nan}" >> "$work/results"
  done
done
python3 - "$work/results" "$work/edits" <<'PY'
import re, statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
edits = open(sys.argv[2]).read()
def med(xs):
    return statistics.median(xs) if xs else float("nan")
load = med([float(x) for x in re.findall(r"models loaded in ([0-9.]+) ms", edits)])
for how in ("one model uploaded", "one model dropped"):
    applied = [float(x) for x in re.findall(r"edit applied in ([0-9.]+) ms \(" + how, edits)]
    frame = [float(x) for x in re.findall(how + r"\), drawn in frame \d+ \(([0-9.]+) ms", edits)]
    print(f"{how}: applied in {med(applied):.1f} ms (median of {len(applied)}), its frame {med(frame):.1f} ms;"
          f" loading every model (what it cost before) {load:.1f} ms: {med(applied) / load:.3f} of it")
fb = med([float(r[1]) for r in rows if r[0] == "base"])
fn = med([float(r[1]) for r in rows if r[0] == "new"])
print(f"kiosk first frame median: base {fb:.1f} ms, new {fn:.1f} ms, new/base {fn / fb:.2f}")
print("first frames:", " ".join(" ".join(r) for r in rows))
print(edits)
PY
