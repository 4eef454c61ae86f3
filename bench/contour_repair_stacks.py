#!/usr/bin/env python3
"""Contour repair on stacks sliced from real meshes (issue 23).

Each mesh is sliced with `bodygen slice` (N planes, along z and x, without
--avoid-self-intersections: folds of the mesh give crossing contours), then
every point is jittered by up to `--jitter` of the stack extent and `--zigzags`
contours per stack get a twisted zig-zag (a figure-eight loop) of 0.01-0.1 % of
the extent inserted in one edge. Each stack is built with --strict (the old
behaviour) and with the default repair; prints per stack: refused or built,
closed, the repairs by kind and the largest distance a repair moved a point
(relative to the extent), which sets the default --repair-tolerance.

usage: bench/contour_repair_stacks.py BODYGEN MESH.obj... [--planes 40 100] [--seed 1]
"""
import argparse
import json
import math
import os
import random
import re
import subprocess
import sys
import tempfile


def extent(stack):
    xs = [p[0] for s in stack["slices"] for c in s["contours"] for p in c["points"]]
    ys = [p[1] for s in stack["slices"] for c in s["contours"] for p in c["points"]]
    return math.hypot(max(xs) - min(xs), max(ys) - min(ys))


def perturb(stack, rng, jitter, zigzags):
    ext = extent(stack)
    for s in stack["slices"]:
        for c in s["contours"]:
            c["points"] = [[x + rng.uniform(-1, 1) * jitter * ext, y + rng.uniform(-1, 1) * jitter * ext]
                           for x, y in c["points"]]
    contours = [c for s in stack["slices"] for c in s["contours"] if len(c["points"]) >= 8]
    for c in rng.sample(contours, min(zigzags, len(contours))):
        pts = c["points"]
        i = rng.randrange(len(pts))
        a, b = pts[i], pts[(i + 1) % len(pts)]
        dx, dy = b[0] - a[0], b[1] - a[1]
        length = math.hypot(dx, dy) or 1.0
        nx, ny = -dy / length, dx / length
        w = rng.uniform(1e-4, 1e-3) * ext  # 0.01-0.1 % of the extent
        # a -> 0.6 along -> back to 0.4 on one side -> 0.4 on the other side -> b: a small twist.
        p = lambda t, off: [a[0] + dx * t + nx * off, a[1] + dy * t + ny * off]
        pts[i + 1:i + 1] = [p(0.6, 0.0), p(0.4, w), p(0.4, -w)]
    return ext


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bodygen")
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--planes", type=int, nargs="+", default=[40, 100])
    ap.add_argument("--axes", nargs="+", default=["z", "x"])
    ap.add_argument("--jitter", type=float, default=2e-5)
    ap.add_argument("--zigzags", type=int, default=5)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    work = tempfile.mkdtemp()
    print("| stack | extent | strict | repaired | closed | repairs | max moved / extent |")
    print("|---|---|---|---|---|---|---|")
    worst = 0.0
    for mesh in args.meshes:
        for axis in args.axes:
            for planes in args.planes:
                name = f"{os.path.splitext(os.path.basename(mesh))[0]}-{axis}{planes}"
                raw = os.path.join(work, name + ".contours.json")
                code, _, err = run([args.bodygen, "slice", mesh, "--planes", str(planes), "--axis", axis, "-o", raw])
                if code:
                    print(f"| {name} | slice failed: {err.strip()} |")
                    continue
                stack = json.load(open(raw))
                ext = perturb(stack, rng, args.jitter, args.zigzags)
                path = os.path.join(work, name + ".zig.contours.json")
                json.dump(stack, open(path, "w"))
                out = os.path.join(work, name + ".obj")
                strict, _, _ = run([args.bodygen, "build", path, "-o", out, "--strict", "--quiet"])
                code, stdout, stderr = run([args.bodygen, "build", path, "-o", out, "--json"])
                if code:
                    print(f"| {name} | {ext:.3g} | {'ok' if strict == 0 else 'refused'} | refused: "
                          f"{stderr.strip().splitlines()[-1]} | | | |")
                    continue
                j = json.loads(stdout)
                closed = all(s["closed_manifold"] for s in j["structures"])
                moved = [float(m) for m in re.findall(r"points moved up to ([0-9.e+-]+)", stderr)]
                rel = max(moved, default=0.0) / ext
                worst = max(worst, rel)
                kinds = ", ".join(f"{k} {v}" for k, v in sorted(j["repairs"].items()))
                print(f"| {name} | {ext:.3g} | {'ok' if strict == 0 else 'refused'} | built | "
                      f"{'yes' if closed else 'NO'} | {kinds} | {rel:.2e} |")
    print(f"\nlargest repair movement: {worst:.2e} of the extent")


if __name__ == "__main__":
    sys.exit(main())
