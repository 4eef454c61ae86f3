#!/usr/bin/env bash
# A full disk never corrupts a bundle: `bodygen pack` of a scene larger than a
# small tmpfs, over a bundle already there, fails (exit 1) and leaves the old
# bundle byte for byte as it was, no temporary files, and a kiosk that still
# shows it. Needs mount(2) (root, not in every container): exit 77 (skipped)
# where a tmpfs cannot be mounted.
#   scripts/check-full-disk.sh BUILD_DIR
set -uo pipefail
. "$(dirname "$0")/full-disk-tmpfs.sh" check-full-disk 512k "${1:-}"
fail() { echo "check-full-disk: $*"; exit 1; }
# The small bundle that fits, then a scene of models that together do not.
mkdir -p "$tmp/small" "$tmp/big"
cp "$ROOT/tests/data/models/smoke.obj" "$tmp/small/"
echo '{"models": [{"name": "smoke", "file": "smoke.obj"}]}' > "$tmp/small/scene.json"
"$BUILD/bin/bodygen" pack "$tmp/small/scene.json" -o "$mnt/exhibit" || fail "the small bundle did not fit"
python3 - "$tmp/big" <<'PY'
import math, sys
d = sys.argv[1]
names = []
for k in range(6):  # six spheres of ~20k triangles, ~1 MB of OBJ each
    n = 100
    lines = []
    for i in range(n + 1):
        t = math.pi * i / n
        for j in range(2 * n):
            p = 2 * math.pi * j / (2 * n)
            lines.append(f"v {math.sin(t)*math.cos(p)+3*k:.6f} {math.cos(t):.6f} {math.sin(t)*math.sin(p):.6f}")
    for i in range(n):
        for j in range(2 * n):
            a = i * 2 * n + j + 1; b = i * 2 * n + (j + 1) % (2 * n) + 1
            lines.append(f"f {a} {b} {b + 2 * n}"); lines.append(f"f {a} {b + 2 * n} {a + 2 * n}")
    open(f"{d}/m{k}.obj", "w").write("\n".join(lines) + "\n")
    names.append(f'{{"name": "m{k}", "file": "m{k}.obj"}}')
open(f"{d}/scene.json", "w").write('{"models": [' + ", ".join(names) + "]}")
PY
before=$(cd "$mnt" && find . -type f -exec md5sum {} + | sort)
"$BUILD/bin/bodygen" pack "$tmp/big/scene.json" -o "$mnt/exhibit" > "$tmp/out" 2>&1
rc=$?
cat "$tmp/out"
[ "$rc" -eq 1 ] || fail "pack onto a full disk exited $rc, expected 1"
grep -q "bundle" "$tmp/out" || fail "the error does not say what failed"
after=$(cd "$mnt" && find . -type f -exec md5sum {} + | sort)
[ "$before" = "$after" ] || { diff <(echo "$before") <(echo "$after"); fail "the disk changed (old bundle altered or temporary files left)"; }
"$BUILD/bin/bodyview" --headless --size 160x100 --frames 3 "$mnt/exhibit/" || fail "the old bundle no longer shows"
echo "check-full-disk: a pack that does not fit failed cleanly; the old bundle is intact and shows"
