#!/usr/bin/env python3
"""Issue 23's time goal: whole process against whole process, per stack.

Stacks: the glmark2 bunny sliced along z at 40 and 100 planes and along x at
100, and a torus (R 1, r 0.35, 160 x 64 quads, turned 20 degrees about x)
along z at 40, each made with `bodygen slice --avoid-self-intersections` (as
bench/reconstruct_vs_vtk.sh / interpolate_vs_vtk.sh do). For each stack and
each repetition, in turn: VTK's whole route (bench/vtk_contours_to_obj.py:
Python start, read the stack, vtkVoxelContoursToSurfaceFilter, write an OBJ),
then `bodygen build STACK -o OUT --quiet` linear (`--interpolate 0`) and with `--interpolate N`,
for the candidate binary and, when --base is given, the baseline binary
alternated with it. Each process is timed the same way: CPU (user + system of
the child, getrusage) and wall. Prints per stack the median [min-max] of each,
VTK's Update() alone, and the ratios of medians interpolated / VTK whole.

usage: bench/time_vs_vtk.py [--bodygen BUILD/bin/bodygen] [--base OTHER/bodygen]
                            [--reps 5] [--rings 3] [--ring-tolerance F] [--stacks bunny-z40,...]

--ring-tolerance F is passed to the candidate's interpolated builds only (the
baseline may predate the option), to time adaptive rings against uniform ones.
"""
import argparse
import math
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
PY = "/usr/bin/python3"  # Debian's python, which has python3-vtk9


def timed(cmd):
    """(cpu seconds, wall seconds, stdout) of one child process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run(cmd, check=True, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, wall, r.stdout


def write_torus(path):
    nu, nv, big, small = 160, 64, 1.0, 0.35
    c, s = math.cos(math.radians(20)), math.sin(math.radians(20))
    with open(path, "w") as f:
        for i in range(nu):
            u = 2 * math.pi * i / nu
            for j in range(nv):
                v = 2 * math.pi * j / nv
                x = (big + small * math.cos(v)) * math.cos(u)
                y = (big + small * math.cos(v)) * math.sin(u)
                z = small * math.sin(v)
                f.write(f"v {x} {y * c - z * s} {y * s + z * c}\n")
        for i in range(nu):
            for j in range(nv):
                a0, a1 = i * nv + j, ((i + 1) % nu) * nv + j
                a2, a3 = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
                f.write(f"f {a0 + 1} {a1 + 1} {a2 + 1}\nf {a0 + 1} {a2 + 1} {a3 + 1}\n")


def fmt(values):
    return f"{statistics.median(values):.3f} [{min(values):.3f}-{max(values):.3f}]"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bodygen", default=os.path.join(HERE, "..", "build", "bin", "bodygen"))
    ap.add_argument("--base")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--rings", type=int, default=3)
    ap.add_argument("--ring-tolerance")
    ap.add_argument("--resolution", type=int, default=256)
    ap.add_argument("--stacks", default="bunny-z40,bunny-z100,bunny-x100,torus-z40")
    args = ap.parse_args()
    binaries = [("ours", args.bodygen)] + ([("base", args.base)] if args.base else [])
    work = tempfile.mkdtemp(prefix="time_vs_vtk.")
    meshes = {"bunny": "/usr/share/glmark2/models/bunny.obj", "torus": os.path.join(work, "torus.obj")}
    write_torus(meshes["torus"])
    print(f"{args.reps} alternated runs; CPU and wall seconds, median [min-max]; --interpolate {args.rings}"
          + (f", ours --ring-tolerance {args.ring_tolerance}" if args.ring_tolerance else ""))
    print("| stack | VTK whole CPU | VTK whole wall | VTK Update() CPU | binary | linear CPU | linear wall |"
          " interpolated CPU | interpolated wall | interp/VTK whole: CPU, wall |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name in args.stacks.split(","):
        mesh, cut = name.split("-")
        stack = os.path.join(work, name + ".contours.json")
        subprocess.run([args.bodygen, "slice", meshes[mesh], "--planes", cut[1:], "--axis", cut[0],
                        "--avoid-self-intersections", "-o", stack], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        t = {"vtk": ([], [], [])}
        for label, _ in binaries:
            t[label] = ([], [], [], [])
        for rep in range(args.reps):
            cpu, wall, out = timed([PY, os.path.join(HERE, "vtk_contours_to_obj.py"), stack,
                                    os.path.join(work, "vtk.obj"), "--resolution", str(args.resolution)])
            t["vtk"][0].append(cpu)
            t["vtk"][1].append(wall)
            t["vtk"][2].append(float(out.split()[-1]))
            for label, binary in binaries if rep % 2 == 0 else binaries[::-1]:  # alternate which goes first
                cpu, wall, _ = timed([binary, "build", stack, "-o", os.path.join(work, label + ".obj"), "--quiet",
                                      "--interpolate", "0"])
                t[label][0].append(cpu)
                t[label][1].append(wall)
                adaptive = ["--ring-tolerance", args.ring_tolerance] if args.ring_tolerance and label == "ours" else []
                cpu, wall, _ = timed([binary, "build", stack, "-o", os.path.join(work, label + "-i.obj"), "--quiet",
                                      "--interpolate", str(args.rings)] + adaptive)
                t[label][2].append(cpu)
                t[label][3].append(wall)
        vc, vw, vu = t["vtk"]
        for label, _ in binaries:
            lc, lw, ic, iw = t[label]
            ratio = f"{statistics.median(ic) / statistics.median(vc):.2f}, {statistics.median(iw) / statistics.median(vw):.2f}"
            print(f"| {name} | {fmt(vc)} | {fmt(vw)} | {fmt(vu)} | {label} | {fmt(lc)} | {fmt(lw)} | {fmt(ic)} |"
                  f" {fmt(iw)} | {ratio} |")
        sys.stdout.flush()
    subprocess.run(["rm", "-rf", work], check=False)
    return 0


if __name__ == "__main__":
    sys.exit(main())
