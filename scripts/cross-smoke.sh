#!/usr/bin/env bash
# The aarch64 cross smoke: cross-build everything with Debian's aarch64-linux-gnu
# toolchain and :arm64 multiarch libraries, then under qemu-aarch64 run the unit
# tests, `bodygen --version`, bodygen on a small stack (output compared with the
# native build), and one headless bodyview frame (softpipe) compared with the
# same frame rendered natively. Usage: scripts/cross-smoke.sh NATIVE_BUILD_DIR
set -euo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
NATIVE=${1:-$ROOT/build}
CROSS=${CROSS_BUILD_DIR:-$ROOT/build-arm64}
JOBS=${JOBS:-$(nproc)}
QEMU=(qemu-aarch64 -L /)  # loader from libc6:arm64, see cmake/toolchain-aarch64-linux-gnu.cmake
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT

echo "--- cross build ($CROSS)"
cmake -S "$ROOT" -B "$CROSS" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/toolchain-aarch64-linux-gnu.cmake" \
    -DBODY_WITH_IMPORT=OFF -DBODY_BUILD_BENCH=OFF >"$WORK/configure.log" 2>&1 || { cat "$WORK/configure.log"; exit 1; }
cmake --build "$CROSS" -j "$JOBS" 2>&1 | tail -5
[ "${PIPESTATUS[0]}" -eq 0 ]

echo "--- what runs (file):"
for b in "$CROSS"/bin/*; do file "$b"; done
file "$CROSS/bin/bodygen" | grep -q 'ARM aarch64' || { echo "bodygen is not an aarch64 binary"; exit 1; }

echo "--- unit tests under qemu-aarch64"
ctest --test-dir "$CROSS" -L unit -j "$JOBS" --output-on-failure --no-tests=error

echo "--- bodygen --version under qemu"
"${QEMU[@]}" "$CROSS/bin/bodygen" --version
[ "$("${QEMU[@]}" "$CROSS/bin/bodygen" --version)" = "$("$NATIVE/bin/bodygen" --version)" ]

# bodygen on a small stack: same mesh from both architectures.
STACK=$ROOT/tests/data/stacks/small.contours.json
if [ -f "$STACK" ] && "$NATIVE/bin/bodygen" --help | grep -q '^  build '; then
    echo "--- bodygen build on $STACK under qemu"
    "${QEMU[@]}" "$CROSS/bin/bodygen" build "$STACK" -o "$WORK/arm64.obj" --quiet
    "$NATIVE/bin/bodygen" build "$STACK" -o "$WORK/native.obj" --quiet
    if cmp -s "$WORK/arm64.obj" "$WORK/native.obj"; then echo "identical OBJ from aarch64 and x86-64"
    else
        "$NATIVE/bin/body_compare_obj" "$WORK/native.obj" "$WORK/arm64.obj" 1e-9
    fi
    if "$NATIVE/bin/bodygen" --help | grep -q '^  lod '; then
        echo "--- bodygen lod under qemu: same bytes on both architectures"
        "${QEMU[@]}" "$CROSS/bin/bodygen" lod "$WORK/native.obj" -o "$WORK/arm64.bpm"
        "$NATIVE/bin/bodygen" lod "$WORK/native.obj" -o "$WORK/native.bpm"
        cmp "$WORK/arm64.bpm" "$WORK/native.bpm" && echo "identical .bpm from aarch64 and x86-64"
    fi
else
    echo "--- (bodygen build not available yet: small-stack check skipped)"
fi

# One headless bodyview frame, softpipe under qemu vs llvmpipe natively.
MODEL=$ROOT/tests/data/models/smoke.obj
if [ -f "$MODEL" ] && "$NATIVE/bin/bodyview" --help | grep -q -- '--screenshot'; then
    echo "--- bodyview headless frame under qemu (softpipe)"
    args=(--platform headless --size 160x120 --model "$MODEL" --style smooth --screenshot)
    GALLIUM_DRIVER=softpipe timeout 300 "${QEMU[@]}" "$CROSS/bin/bodyview" "${args[@]}" "$WORK/arm64.png"
    "$NATIVE/bin/bodyview" "${args[@]}" "$WORK/native.png"
    "$NATIVE/bin/body_compare_png" "$WORK/native.png" "$WORK/arm64.png" --max-mean 3 --max-bad-fraction 0.02
else
    echo "--- (bodyview --screenshot not available yet: frame comparison skipped)"
fi
echo "cross smoke: ok"
