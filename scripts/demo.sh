#!/usr/bin/env bash
# The main job on the sample data (README: ./setup.sh demo): build the AAL brain
# atlas into meshes, progressive meshes and a kiosk bundle, then open the kiosk:
# a fullscreen window when a display exists, the DRM/KMS console on a board
# without one, and otherwise headless screenshots into build/sample/screenshots/.
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
BIN=$ROOT/build/bin
OUT=$ROOT/build/sample
"$BIN/bodygen" --version
"$ROOT/scripts/build-sample.sh" "$BIN/bodygen" "$OUT"
BUNDLE=$OUT/bundle

if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && [ -z "${BODY_DEMO_HEADLESS:-}" ]; then
    echo "demo: opening the kiosk on the display (admin exit: 5 taps in the top-left corner, or Ctrl+C)"
    exec "$BIN/bodyview" --platform glfw "$BUNDLE"
fi
if ls /dev/dri/card* >/dev/null 2>&1 && [ -z "${BODY_DEMO_HEADLESS:-}" ] && [ -t 0 ]; then
    echo "demo: no display server; opening the kiosk on the console (DRM/KMS)"
    exec "$BIN/bodyview" --platform drm "$BUNDLE"
fi

SHOTS=$OUT/screenshots
mkdir -p "$SHOTS"
echo "demo: no display: headless screenshots into $SHOTS"
"$BIN/bodyview" --headless --size 1280x800 "$BUNDLE" --screenshot "$SHOTS/brain_smooth.png"
for style in hatching lines wireframe; do
    "$BIN/bodyview" --headless --size 1280x800 "$BUNDLE" --style "$style" --screenshot "$SHOTS/brain_$style.png"
done
# A visitor taps a region: the label card appears.
REPLAY=$(mktemp)
trap 'rm -f "$REPLAY"' EXIT
printf 'size 1280 800\n0.50 down 1 560 330\n0.55 up 1 560 330\n2.0 end\n' >"$REPLAY"
"$BIN/bodyview" --headless --size 1280x800 "$BUNDLE" --replay "$REPLAY" --screenshot "$SHOTS/brain_label.png"
ls -1 "$SHOTS"
echo "demo: done. Open the bundle on a kiosk with: build/bin/bodyview $BUNDLE"
