#!/usr/bin/env python3
"""Hostile-input sweep (issue 30): generates bad inputs across every input
class, runs each command on them under a time limit (30 s) and an
address-space limit (4 GiB), interrupts writes with SIGINT/SIGTERM/SIGKILL
(class "interrupted write"), and checks:

  crash     the process ended on a signal
  hang      it ran past the time limit
  leftover  it failed and left a file behind (output or temporary)
  destroyed an input file changed
  missed    (interrupted writes) the write ended before it could be interrupted
  accepted  a bad input was accepted (exit 0) where the format forbids it
  message   a refusal that is not exit 2 with exactly one line naming the
            file (or the flag) it refuses

  scripts/hostile_sweep.py BUILD_DIR [--quick] [--only CLASS] [--keep] [-v]

--quick runs a fixed subset (every 9th case of each class, 3 interrupted
writes; not the 10,000-model bundle; ctest
hostile_sweep_quick, label cli). Exit 0 when no case failed a check (a
"missed" interruption is reported, not failed). The same seed gives the same inputs.
"""
import argparse
import base64
import gzip
import json
import math
import os
import random
import resource
import shutil
import signal
import stat
import struct
import subprocess
import sys
import tempfile
import time
import hashlib
import collections

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TIME_LIMIT = 30
AS_LIMIT = 4 << 30


class Case:
    """One run: `argv` in a fresh directory holding `files` (name -> bytes,
    or a callable making a special file). `expect`: 'refuse' (exit 2, one line
    naming `needle`), 'fail' (exit 1 or 2, one line naming `needle`),
    'skip' (the kiosk goes on: exit 0 or 2, at least one line naming
    `needle`), 'any' (only crash/hang/leftover/destroyed are checked)."""

    def __init__(self, cls, name, argv, files, expect="refuse", needle=None, outputs=(), slow=False):
        self.cls, self.name, self.argv, self.files = cls, name, argv, files
        self.expect, self.needle, self.outputs, self.slow = expect, needle, outputs, slow


# ------------------------------------------------------------ base inputs

def circle(n, r, cx=0.0, cy=0.0):
    return [[round(cx + r * math.cos(2 * math.pi * i / n), 4), round(cy + r * math.sin(2 * math.pi * i / n), 4)]
            for i in range(n)]


def stack(slices, structures=None):
    return {"format": "bodygen.contours", "version": 1,
            "structures": structures if structures is not None else [{"id": "a"}], "slices": slices}


def good_stack():
    return stack([{"z": z, "contours": [{"structure": "a", "points": circle(24, 10)}]} for z in (0, 2, 4)])


def nifti(dims=(8, 8, 8), datatype=2, bitpix=8, vox_offset=352.0, magic=b"n+1\0", sizeof_hdr=348,
          pixdim=(1.0, 1.0, 1.0), data=None, dim0=3, scl_slope=1.0, sform_code=0, srow=None):
    h = bytearray(352)
    struct.pack_into("<i", h, 0, sizeof_hdr)
    d = [dim0] + list(dims) + [1] * (7 - len(dims))
    struct.pack_into("<8h", h, 40, *d[:8])
    struct.pack_into("<hh", h, 70, datatype, bitpix)
    struct.pack_into("<8f", h, 76, 1.0, *pixdim, 1.0, 1.0, 1.0, 1.0)
    struct.pack_into("<f", h, 108, vox_offset)
    struct.pack_into("<f", h, 112, scl_slope)
    struct.pack_into("<h", h, 254, sform_code)
    if srow:
        struct.pack_into("<12f", h, 280, *srow)
    h[344:348] = magic
    if data is None:
        nx, ny, nz = dims[0], dims[1], dims[2]
        data = bytes(1 if 2 <= x < nx - 2 and 2 <= y < ny - 2 and 2 <= z < nz - 2 else 0
                     for z in range(nz) for y in range(ny) for x in range(nx))
    return bytes(h) + data


def obj_tetra(extra=""):
    return ("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n" + extra).encode()


TETRA = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
TETRA_F = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3)]


def stl_binary(count=None, tris=None):
    tris = tris if tris is not None else [[TETRA[i] for i in f] for f in TETRA_F]
    out = bytearray(80) + struct.pack("<I", len(tris) if count is None else count)
    for t in tris:
        out += struct.pack("<3f", 0, 0, 0)
        for p in t:
            out += struct.pack("<3f", *p)
        out += b"\0\0"
    return bytes(out)


def ply(nv=4, nf=4, fmt="ascii 1.0", body=None, face_prop="list uchar int vertex_indices"):
    head = (f"ply\nformat {fmt}\nelement vertex {nv}\nproperty float x\nproperty float y\nproperty float z\n"
            f"element face {nf}\nproperty {face_prop}\nend_header\n")
    if body is None:
        body = "".join(f"{x} {y} {z}\n" for x, y, z in TETRA) + "".join(f"3 {a} {b} {c}\n" for a, b, c in TETRA_F)
    return (head + body).encode()


def gltf_tetra(positions=None, indices=None, count=None, index_count=None, uri=None, doc_edit=None):
    """A tetrahedron as .gltf with its buffer embedded (or at `uri`); fields overridable to break it."""
    pos = positions if positions is not None else TETRA
    idx = indices if indices is not None else [i for f in TETRA_F for i in f]
    data = b"".join(struct.pack("<3f", *p) for p in pos) + b"".join(struct.pack("<H", i) for i in idx)
    npos = 12 * len(pos)
    doc = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "scene": 0, "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "buffers": [{"byteLength": len(data),
                        "uri": uri or "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
           "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": npos},
                           {"buffer": 0, "byteOffset": npos, "byteLength": len(data) - npos}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "type": "VEC3",
                          "count": len(pos) if count is None else count, "min": [0, 0, 0], "max": [1, 1, 1]},
                         {"bufferView": 1, "componentType": 5123, "type": "SCALAR",
                          "count": len(idx) if index_count is None else index_count}]}
    if doc_edit:
        doc_edit(doc)
    return json.dumps(doc).encode()


def glb(json_bytes, magic=b"glTF", length=None):
    """The .gltf's embedded buffer moved to the BIN chunk of a .glb."""
    doc = json.loads(json_bytes)
    data = base64.b64decode(doc["buffers"][0].pop("uri").split(",", 1)[1])
    json_bytes = json.dumps(doc).encode()
    json_bytes += b" " * (-len(json_bytes) % 4)
    data += b"\0" * (-len(data) % 4)
    body = struct.pack("<I", len(json_bytes)) + b"JSON" + json_bytes + struct.pack("<I", len(data)) + b"BIN\0" + data
    total = 12 + len(body)
    return magic + struct.pack("<II", 2, total if length is None else length) + body


def fifo(path):
    os.mkfifo(path)


def dev_zero(path):
    os.symlink("/dev/zero", path)


def directory(path):
    os.mkdir(path)


def dangling(path):
    os.symlink("/nonexistent/target", path)


SPECIAL = [("fifo", fifo), ("devzero", dev_zero), ("dir", directory), ("dangling", dangling)]


# ------------------------------------------------------------ generators

def mutate_bytes(rng, data, n):
    """n structured corruptions of `data`: truncations, flips, insertions."""
    out = []
    for i in range(n):
        b = bytearray(data)
        kind = i % 4
        if kind == 0 and len(b) > 2:
            b = b[:rng.randrange(1, len(b))]
        elif kind == 1:
            for _ in range(rng.randint(1, 8)):
                b[rng.randrange(len(b))] = rng.randrange(256)
        elif kind == 2:
            at = rng.randrange(len(b) + 1)
            b[at:at] = bytes(rng.randrange(256) for _ in range(rng.randint(1, 64)))
        else:
            at = rng.randrange(len(b))
            b[at:at + rng.randint(1, 32)] = b""
        out.append(bytes(b))
    return out


def contour_cases(rng):
    cls = "contour stack"
    cases = []
    good = good_stack()

    def add(name, doc_or_bytes, expect="refuse"):
        data = doc_or_bytes if isinstance(doc_or_bytes, bytes) else json.dumps(doc_or_bytes).encode()
        for cmd in (["build", "in.contours.json", "-o", "out.obj", "--quiet"], ["check", "in.contours.json"]):
            cases.append(Case(cls, f"{cmd[0]}: {name}", cmd, {"in.contours.json": data}, expect, "in.contours.json",
                              outputs=("out.obj",) if expect != "refuse" else ()))

    def with_points(pts, zs=(0, 2, 4)):
        return stack([{"z": z, "contours": [{"structure": "a", "points": pts}]} for z in zs])

    for mag in ("1e100", "1e154", "1e200", "1e308", "-1e300", "1e8", "-1e8"):
        pts = circle(12, 10)
        pts[3] = [float(mag), 1.0]
        add(f"coordinate {mag}", with_points(pts))
    for gap in ("1e8", "1e154", "1e300"):
        add(f"slice gap {gap}", with_points(circle(12, 10), zs=(0, float(gap))))
    add("z NaN", json.dumps(with_points(circle(12, 10))).replace('"z": 2', '"z": NaN').encode())
    add("coordinate Infinity", json.dumps(with_points(circle(12, 10))).replace("10.0,", "Infinity,", 1).encode())
    add("coordinate 1e999", json.dumps(with_points(circle(12, 10))).replace("10.0,", "1e999,", 1).encode())
    add("two points", with_points([[0, 0], [1, 1]]))
    add("one point", with_points([[0, 0]]))
    add("no points", with_points([]))
    add("all points equal", with_points([[1, 1]] * 10))
    add("collinear", with_points([[i, i] for i in range(10)]))
    add("point with 1 value", with_points([[0, 0], [1], [1, 1]]))
    add("point with 3 values", with_points([[0, 0, 0], [1, 0, 0], [1, 1, 0]]))
    add("point is a string", with_points([[0, 0], "x", [1, 1]]))
    add("coordinate is a string", with_points([["0", 0], [1, 0], [1, 1]]))
    add("coordinate is null", with_points([[None, 0], [1, 0], [1, 1]]))
    add("coordinate is bool", with_points([[True, 0], [1, 0], [1, 1]]))
    add("duplicate z", with_points(circle(12, 10), zs=(0, 0, 2)), expect="any")  # repaired: a union
    add("z descending", with_points(circle(12, 10), zs=(4, 2, 0)), expect="any")
    add("unknown structure", stack([{"z": 0, "contours": [{"structure": "zz", "points": circle(12, 5)}]}]))
    add("no structures", stack([{"z": 0, "contours": [{"structure": "a", "points": circle(12, 5)}]}], []))
    add("duplicate structure id", stack(good["slices"], [{"id": "a"}, {"id": "a"}]))
    add("structure id empty", stack(good["slices"], [{"id": ""}]))
    add("structure id control chars", stack(good["slices"], [{"id": "a"}, {"id": "\x1b[31mred\x07"}]), expect="any")
    add("color 50", stack(good["slices"], [{"id": "a", "color": [50, 0, 0]}]))
    add("color NaN-like", stack(good["slices"], [{"id": "a", "color": [-1, 0, 0]}]))
    add("color 2 values", stack(good["slices"], [{"id": "a", "color": [1, 0]}]))
    add("no slices", stack([]))
    add("slices not array", {"format": "bodygen.contours", "version": 1, "structures": [{"id": "a"}], "slices": 3})
    add("slice without z", stack([{"contours": [{"structure": "a", "points": circle(12, 5)}]}]))
    add("slice without contours", stack([{"z": 0}]))
    add("wrong format", dict(good, format="other"))
    add("version 99", dict(good, version=99))
    add("version string", dict(good, version="1"))
    add("top is array", b"[1, 2, 3]")
    add("top is number", b"42")
    add("empty file", b"")
    add("whitespace only", b"   \n\t  ")
    add("BOM", b"\xef\xbb\xbf" + json.dumps(good).encode(), expect="any")
    add("UTF-16", json.dumps(good).encode("utf-16"))
    add("nested arrays 100000 deep", b"[" * 100000 + b"]" * 100000)
    add("nested objects 100000 deep", b'{"a":' * 100000 + b"1" + b"}" * 100000)
    add("huge number literal", json.dumps(good).replace("10.0", "1" * 5000, 1).encode())
    add("string with NUL", json.dumps(good).replace('"a"', '"a\\u0000b"', 1).encode())
    add("invalid UTF-8", json.dumps(good).encode().replace(b'"a"', b'"\xff\xfe"', 1))
    add("trailing garbage", json.dumps(good).encode() + b"}}}")
    add("unterminated string", json.dumps(good).encode()[:-30] + b'"abc')
    add("binary garbage", bytes(rng.randrange(256) for _ in range(4096)))
    add("crossing self (bow tie)", with_points([[0, 0], [10, 10], [10, 0], [0, 10]]), expect="any")
    add("400 concentric rings", stack([{"z": z, "contours": [{"structure": "a", "points": circle(32, 1 + 0.5 * k)}
                                                               for k in range(400)]} for z in (0, 2, 4)]), expect="any")
    add("hole outside outer", stack([{"z": 0, "contours": [{"structure": "a", "points": circle(12, 5)},
                                                           {"structure": "a", "points": circle(12, 1, 50, 50),
                                                            "hole": True}]}]), expect="any")
    add("unknown contour key", stack([{"z": 0, "contours": [{"structure": "a", "points": circle(12, 5), "hole": "yes"}]}]),
        expect="any")  # unknown keys are ignored (forward compatible)
    add("links garbage", dict(good, links="x"))
    add("links to nowhere", dict(good, links=[{"from": [99, 0], "to": [100, 0]}]))
    # Truncations and corruptions of a good stack.
    data = json.dumps(good).encode()
    for i, m in enumerate(mutate_bytes(rng, data, 48)):
        add(f"mutation {i}", m, expect="any")
    for sname, make in SPECIAL:
        for cmd in (["build", "in.contours.json", "-o", "out.obj", "--quiet"], ["check", "in.contours.json"]):
            cases.append(Case(cls, f"{cmd[0]}: input is {sname}", cmd, {"in.contours.json": make}, "refuse",
                              "in.contours.json"))
    cases.append(Case(cls, "build: missing input", ["build", "nope.contours.json", "-o", "out.obj"], {}, "refuse",
                      "nope.contours.json"))
    return cases


def nifti_cases(rng):
    cls = "label volume/table"
    cases = []

    def add(name, data, gz=False, expect="refuse"):
        fname = "in.nii.gz" if gz else "in.nii"
        files = {fname: gzip.compress(data) if gz else data}
        for cmd in (["contours", fname, "-o", "out.contours.json", "--quiet"],
                    ["build", fname, "-o", "out.obj", "--quiet"]):
            cases.append(Case(cls, f"{cmd[0]}: {name}", cmd, files, expect, fname))

    add("dims negative", nifti(dims=(-8, 8, 8)))
    add("dims zero", nifti(dims=(0, 8, 8)))
    add("dim0 zero", nifti(dim0=0))
    add("dim0 9", nifti(dim0=9))
    add("declares 2048x2048x128 in a small file", nifti(dims=(2048, 2048, 128), data=b"\0" * 1024))
    add("declares 2048x2048x128 gz", nifti(dims=(2048, 2048, 128), data=b"\0" * 65536), gz=True)
    add("declares 32767^3", nifti(dims=(32767, 32767, 32767), data=b"\0" * 64), expect="fail")  # memory budget: 1
    add("wrong magic", nifti(magic=b"xyz\0"))
    add("sizeof_hdr 0", nifti(sizeof_hdr=0))
    add("sizeof_hdr 540 (NIfTI-2 claim)", nifti(sizeof_hdr=540))
    add("datatype 0", nifti(datatype=0))
    add("datatype 9999", nifti(datatype=9999))
    add("bitpix mismatch", nifti(bitpix=64))
    add("float32 NaN voxels", nifti(datatype=16, bitpix=32, data=struct.pack("<f", float("nan")) * 512))
    add("float64 inf voxels", nifti(datatype=64, bitpix=64, data=struct.pack("<d", float("inf")) * 512))
    add("complex datatype", nifti(datatype=32, bitpix=64, data=b"\0" * 4096))
    add("rgb datatype", nifti(datatype=128, bitpix=24, data=b"\1" * 1536))
    add("vox_offset beyond file", nifti(vox_offset=1e6))
    add("vox_offset negative", nifti(vox_offset=-100))
    add("vox_offset NaN", nifti(vox_offset=float("nan")))
    add("vox_offset inside header", nifti(vox_offset=100))
    add("truncated data", nifti()[:352 + 100])
    add("truncated header", nifti()[:200])
    add("header only", nifti()[:348])
    add("pixdim zero", nifti(pixdim=(0.0, 1.0, 1.0)))
    add("pixdim negative", nifti(pixdim=(-1.0, 1.0, 1.0)), expect="any")
    add("pixdim NaN", nifti(pixdim=(float("nan"), 1.0, 1.0)))
    add("pixdim 1e30", nifti(pixdim=(1e30, 1.0, 1.0)))
    add("scl_slope NaN", nifti(scl_slope=float("nan")), expect="any")
    add("sform NaN", nifti(sform_code=1, srow=[float("nan")] * 12))
    add("sform singular", nifti(sform_code=1, srow=[0.0] * 12))
    add("sform 1e30", nifti(sform_code=1, srow=[1e30, 0, 0, 0, 0, 1e30, 0, 0, 0, 0, 1e30, 0]))
    add("all zero labels", nifti(data=b"\0" * 512))
    add("label 255 everywhere", nifti(data=b"\xff" * 512), expect="any")
    add("1-voxel-thick label", nifti(dims=(1, 1, 1), data=b"\1"), expect="any")
    add("empty file", b"")
    add("text file", b"hello, this is not a volume\n" * 20)
    gz_good = gzip.compress(nifti())
    for i, cut in enumerate((10, 30, len(gz_good) // 2, len(gz_good) - 4)):
        cases.append(Case(cls, f"contours: truncated gz {i}", ["contours", "in.nii.gz", "-o", "out.json", "--quiet"],
                          {"in.nii.gz": gz_good[:cut]}, "refuse", "in.nii.gz"))
    cases.append(Case(cls, "contours: gz of garbage", ["contours", "in.nii.gz", "-o", "out.json", "--quiet"],
                      {"in.nii.gz": gzip.compress(bytes(rng.randrange(256) for _ in range(2000)))}, "refuse",
                      "in.nii.gz"))
    cases.append(Case(cls, "contours: gz bomb (1 GB of zeros after the header)",
                      ["contours", "in.nii.gz", "-o", "out.json", "--quiet"],
                      {"in.nii.gz": gzip.compress(nifti()[:348] + b"\0" * (64 << 20))}, "refuse", "in.nii.gz"))
    for i, m in enumerate(mutate_bytes(rng, nifti(), 40)):
        cases.append(Case(cls, f"contours: header mutation {i}", ["contours", "in.nii", "-o", "out.json", "--quiet"],
                          {"in.nii": m}, "any", "in.nii"))
    # Label tables.
    tables = {
        "table binary garbage": bytes(rng.randrange(256) for _ in range(512)),
        "table label not a number": b"x cube\n",
        "table negative label": b"-5 cube\n",
        "table label 1e30": b"100000000000000000000000000000 cube\n",
        "table duplicate label": b"1 cube\n1 other\n",
        "table no name": b"1\n",
        "table control characters": b"1 cu\x1b[2Jbe\x07\n",
        "table empty": b"",
        "table NUL bytes": b"1 cu\0be\n",
        "table 1 MB line": b"1 " + b"a" * (1 << 20) + b"\n",
        "table color 999": b"1 cube 999 0 0\n",
    }
    for name, t in tables.items():
        for cmd in (["contours", "in.nii", "-o", "out.json", "--quiet"], ["build", "in.nii", "-o", "out.obj", "--quiet"]):
            cases.append(Case(cls, f"{cmd[0]}: {name}", cmd + ["--labels", "labels.txt"],
                              {"in.nii": nifti(), "labels.txt": t}, "any", "labels.txt"))
    for sname, make in SPECIAL:
        cases.append(Case(cls, f"contours: input is {sname}", ["contours", "in.nii", "-o", "out.json"],
                          {"in.nii": make}, "refuse", "in.nii"))
        cases.append(Case(cls, f"contours: table is {sname}", ["contours", "in.nii", "-o", "out.json", "--labels",
                                                               "labels.txt"],
                          {"in.nii": nifti(), "labels.txt": make}, "refuse", "labels.txt"))
    return cases


def rtstruct_cases(rng):
    cls = "RT-STRUCT"
    cases = []
    base = open(os.path.join(ROOT, "tests/fuzz/seeds/fuzz_rtstruct/rtstruct.dcm"), "rb").read()

    def add(name, data, expect="refuse"):
        for cmd in (["contours", "in.dcm", "-o", "out.json", "--quiet"], ["build", "in.dcm", "-o", "out.obj", "--quiet"]):
            cases.append(Case(cls, f"{cmd[0]}: {name}", cmd, {"in.dcm": data}, expect, "in.dcm"))

    add("empty file", b"")
    add("preamble only", b"\0" * 128 + b"DICM")
    add("not DICOM", b"hello" * 100)
    add("truncated to 200", base[:200])
    add("truncated to half", base[:len(base) // 2])
    add("truncated by 10", base[:-10])
    # Contour Data (3006,0050) point counts that disagree with the data: bump
    # the Number of Contour Points (3006,0046) values.
    tag = b"\x06\x30\x46\x00"
    at = base.find(tag)
    if at >= 0:  # explicit VR: tag (4), "IS" (2), length (2), then the digits
        b = bytearray(base)
        b[at + 8:at + 10] = b"99"
        add("point count disagrees", bytes(b))
    for i, m in enumerate(mutate_bytes(rng, base, 36)):
        add(f"mutation {i}", m, expect="any")
    for sname, make in SPECIAL:
        cases.append(Case(cls, f"contours: input is {sname}", ["contours", "in.dcm", "-o", "out.json"],
                          {"in.dcm": make}, "refuse", "in.dcm"))
    return cases


def mesh_file_cases(cls, name, fname, data, expect):
    """One mesh file through both commands that read meshes: lod and exhibit."""
    return [Case(cls, f"{cmd[0]}: {name}", cmd, {fname: data}, expect, fname)
            for cmd in (["lod", fname, "-o", "out.bpm", "--quiet"], ["exhibit", fname, "-o", "bundle/", "--quiet"])]


def mesh_cases(rng):
    cls = "OBJ/STL/PLY"
    cases = []

    def add(name, fname, data, expect="refuse"):
        cases.extend(mesh_file_cases(cls, name, fname, data, expect))

    bad_obj = {
        "nan coordinate": "v nan 0 0\n", "inf coordinate": "v inf 0 0\n", "word coordinate": "v one 0 0\n",
        "missing coordinate": "v 1 2\n", "face index 1e20": "f 1 2 100000000000000000000\n",
        "face index 0": "f 0 1 2\n", "face index beyond": "f 1 2 99\n", "face index -99": "f -99 1 2\n",
        "2-vertex face": "f 1 2\n", "face word": "f a b c\n", "1e300 coordinate": "v 1e300 0 0\n",
        "1e400 coordinate": "v 1e400 0 0\n", "face index float": "f 1.5 2 3\n",
        "texture index undefined": "f 1/9 2/9 3/9\n", "normal index undefined": "vn 0 0 1\nf 1//2 2//1 3//1\n",
        "normal index word": "f 1//x 2 3\n", "corner with 4 parts": "f 1/1/1/1 2 3\n",
        "vertex with 5 values": "v 1 2 3 4 5\n", "texture coordinate nan": "vt nan 0\n",
        "normal with 2 values": "vn 0 1\n",
    }
    for name, extra in bad_obj.items():
        add(f"OBJ {name}", "in.obj", obj_tetra(extra))
    add("OBJ empty", "in.obj", b"")
    add("OBJ comments only", "in.obj", b"# nothing\n")
    add("OBJ vertices only", "in.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    add("OBJ binary garbage", "in.obj", bytes(rng.randrange(256) for _ in range(4096)))
    add("OBJ 10 MB line", "in.obj", obj_tetra("# " + "x" * (10 << 20) + "\n"), expect="any")
    add("OBJ all faces degenerate", "in.obj", b"v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n", expect="any")
    add("OBJ NUL byte", "in.obj", obj_tetra().replace(b"v 1 0 0", b"v 1\0 0 0"))
    for i, m in enumerate(mutate_bytes(rng, open(os.path.join(ROOT, "tests/data/models/smoke.obj"), "rb").read(), 20)):
        add(f"OBJ mutation {i}", "in.obj", m, expect="any")
    add("STL count 1e9", "in.stl", stl_binary(count=1000000000))
    add("STL count 0", "in.stl", stl_binary(count=0))
    add("STL truncated", "in.stl", stl_binary()[:100])
    add("STL NaN vertex", "in.stl", stl_binary(tris=[[(float("nan"), 0, 0), (1, 0, 0), (0, 1, 0)]]))
    add("STL ASCII truncated", "in.stl", b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n")
    add("STL empty", "in.stl", b"")
    add("STL header only", "in.stl", b"\0" * 80)
    for i, m in enumerate(mutate_bytes(rng, stl_binary(), 10)):
        add(f"STL mutation {i}", "in.stl", m, expect="any")
    add("PLY vertex count 1e12", "in.ply", ply(nv=10 ** 12))
    add("PLY face count 1e12", "in.ply", ply(nf=10 ** 12))
    add("PLY negative count", "in.ply", ply(nv=-4))
    add("PLY unknown format", "in.ply", ply(fmt="weird 1.0"))
    add("PLY face index 99", "in.ply", ply(body="".join(f"{x} {y} {z}\n" for x, y, z in TETRA) + "3 0 1 99\n" * 4))
    add("PLY binary truncated", "in.ply", ply(fmt="binary_little_endian 1.0", body="\0" * 10))
    add("PLY list length 255", "in.ply", ply(body="".join(f"{x} {y} {z}\n" for x, y, z in TETRA) + "255 0 1 2\n" * 4))
    rows = "".join(f"{x} {y} {z}\n" for x, y, z in TETRA)
    add("PLY list longer than its row", "in.ply", ply(body=rows + "3 0 1 2 3\n" * 4))
    add("PLY rows missing", "in.ply", ply(nf=6))
    add("PLY rows left over", "in.ply", ply(nf=3))
    add("PLY vertex row short", "in.ply", ply(body="".join(f"{x} {y}\n" for x, y, z in TETRA) + "3 0 1 2\n" * 4))
    add("PLY NaN vertex", "in.ply", ply(body="nan 0 0\n" + rows[6:] + "3 0 1 2\n" * 4))
    add("PLY list count 300 in uchar", "in.ply", ply(body=rows + "300 0 1 2\n" * 4))
    bply = lambda n, extra=b"": (ply(fmt="binary_little_endian 1.0", body="")  # noqa: E731
                                 + b"".join(struct.pack("<3f", *p) for p in TETRA)
                                 + b"".join(struct.pack("<B3i", n, *f) for f in TETRA_F) + extra)
    add("PLY binary bytes after the rows", "in.ply", bply(3, b"\0" * 9))
    add("PLY binary list count 9", "in.ply", bply(9))
    add("PLY binary list count 2", "in.ply", bply(2))
    add("STL trailing bytes", "in.stl", stl_binary() + b"\0" * 50)
    add("STL count wraps 32 bits", "in.stl", stl_binary(count=4 + 2 ** 31))
    add("STL binary header says solid", "in.stl", b"solid x" + stl_binary()[7:] + b"\0" * 3)
    facet = "facet normal 0 0 1\nouter loop\n{}endloop\nendfacet\n"
    three = "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
    add("STL ASCII 4-vertex facet", "in.stl", ("solid x\n" + facet.format(three + "vertex 1 1 0\n") +
                                              "endsolid x\n").encode())
    add("STL ASCII 2-vertex facet", "in.stl", ("solid x\n" + facet.format(three[:28]) + "endsolid x\n").encode())
    add("STL ASCII no endsolid", "in.stl", ("solid x\n" + facet.format(three)).encode())
    add("STL ASCII garbage after endsolid", "in.stl", ("solid x\n" + facet.format(three) +
                                                       "endsolid x\nrubbish 1 2\n").encode())
    add("STL ASCII word vertex", "in.stl", ("solid x\n" + facet.format(three.replace("1 0 0", "one 0 0")) +
                                            "endsolid x\n").encode())
    add("STL ASCII no facets", "in.stl", b"solid x\nendsolid x\n")
    add("PLY no end_header", "in.ply", b"ply\nformat ascii 1.0\nelement vertex 3\n")
    add("PLY empty", "in.ply", b"")
    for i, m in enumerate(mutate_bytes(rng, ply(), 10)):
        add(f"PLY mutation {i}", "in.ply", m, expect="any")
    for sname, make in SPECIAL:
        cases.append(Case(cls, f"lod: input is {sname}", ["lod", "in.obj", "-o", "out.bpm"], {"in.obj": make},
                          "refuse", "in.obj"))
    # Random triangles (the simplifier on garbage): bounded, with or without success.
    tri = "".join(f"v {rng.random()} {rng.random()} {rng.random()}\n" for _ in range(6000))
    tri += "".join(f"f {3 * i + 1} {3 * i + 2} {3 * i + 3}\n" for i in range(2000))
    cases.append(Case(cls, "lod: 2000 random triangles", ["lod", "in.obj", "-o", "out.bpm", "--quiet"],
                      {"in.obj": tri.encode()}, "any", "in.obj", outputs=("out.bpm",)))
    return cases


def gltf_cases(rng):
    """glTF (.gltf/.glb) through lod and exhibit: assimp reads it; each refusal one located line."""
    cls = "glTF"
    cases = []

    def add(name, fname, data, expect="refuse"):
        cases.extend(mesh_file_cases(cls, name, fname, data, expect))

    add("glTF good tetrahedron", "in.gltf", gltf_tetra(), expect="any")
    add("glTF empty", "in.gltf", b"")
    add("glTF not JSON", "in.gltf", b"{ this is not json")
    add("glTF no meshes", "in.gltf", json.dumps({"asset": {"version": "2.0"}}).encode())
    add("glTF version 1.0", "in.gltf", gltf_tetra(doc_edit=lambda d: d["asset"].update(version="1.0")))
    add("glTF index beyond the vertices", "in.gltf", gltf_tetra(indices=[0, 1, 99] * 4))
    # assimp alone drops the one bad face and reads the rest; gltf_check refuses it at its element.
    one_beyond = gltf_tetra(indices=[0, 2, 1, 0, 1, 3, 1, 2, 3, 2, 0, 99])
    add("glTF one index beyond, three faces good", "in.gltf", one_beyond)
    add("glb one index beyond, three faces good", "in.glb", glb(one_beyond))
    add("glTF points mode", "in.gltf", gltf_tetra(doc_edit=lambda d: d["meshes"][0]["primitives"][0].update(mode=0)))
    add("glTF float indices", "in.gltf",
        gltf_tetra(doc_edit=lambda d: d["accessors"][1].update(componentType=5126, count=6)))
    add("glTF POSITION of shorts", "in.gltf",
        gltf_tetra(doc_edit=lambda d: d["accessors"][0].update(componentType=5122)))
    add("glTF view beyond its buffer", "in.gltf",
        gltf_tetra(doc_edit=lambda d: d["bufferViews"][1].update(byteLength=4000)))
    add("glTF accessor offset beyond its view", "in.gltf",
        gltf_tetra(doc_edit=lambda d: d["accessors"][1].update(byteOffset=22)))
    add("glTF stride below the element", "in.gltf",
        gltf_tetra(doc_edit=lambda d: d["bufferViews"][0].update(byteStride=4)))
    add("glTF sparse indices", "in.gltf", gltf_tetra(doc_edit=lambda d: d["accessors"][1].update(
        sparse={"count": 1, "indices": {"bufferView": 1, "componentType": 5123},
                "values": {"bufferView": 1}})))
    add("glTF index count not a multiple of 3", "in.gltf", gltf_tetra(index_count=11))
    add("glTF accessor count beyond its view", "in.gltf", gltf_tetra(count=1000))
    add("glTF index count beyond its view", "in.gltf", gltf_tetra(index_count=1000))
    add("glTF NaN position", "in.gltf", gltf_tetra(positions=[(float("nan"), 0, 0)] + TETRA[1:]))
    add("glTF buffer file missing", "in.gltf", gltf_tetra(uri="missing.bin"))
    add("glTF base64 truncated", "in.gltf", gltf_tetra().replace(b'AAAA', b'', 3))
    add("glTF accessor index 7", "in.gltf",
        gltf_tetra(doc_edit=lambda d: d["meshes"][0]["primitives"][0]["attributes"].update(POSITION=7)))
    add("glb good tetrahedron", "in.glb", glb(gltf_tetra()), expect="any")
    add("glb wrong magic", "in.glb", glb(gltf_tetra(), magic=b"glTX"))
    add("glb length field too long", "in.glb", glb(gltf_tetra(), length=1 << 30))
    add("glb truncated", "in.glb", glb(gltf_tetra())[:40])
    for i, m in enumerate(mutate_bytes(rng, gltf_tetra(), 10)):
        add(f"glTF mutation {i}", "in.gltf", m, expect="any")
    return cases


def bpm_cases(rng, base_bpm):
    cls = ".bpm"
    cases = []

    def add(name, data, expect="refuse", tools=("info", "export", "view")):
        if "info" in tools:
            cases.append(Case(cls, f"info: {name}", ["info", "in.bpm"], {"in.bpm": data}, expect, "in.bpm"))
        if "export" in tools:
            cases.append(Case(cls, f"export: {name}", ["export", "in.bpm", "-o", "out.obj", "--quiet"],
                              {"in.bpm": data}, expect, "in.bpm"))
        if "view" in tools:
            cases.append(Case(cls, f"bodyview --model: {name}",
                              ["@bodyview", "--headless", "--size", "64x48", "--model", "in.bpm", "--screenshot",
                               "out.png"], {"in.bpm": data}, "fail" if expect == "refuse" else expect, "in.bpm"))

    add("empty", b"")
    add("magic only", base_bpm[:4])
    add("header only", base_bpm[:16])
    for k in (1, 5, 11):
        add(f"{k} bytes after END.", base_bpm + b"\0" * k, tools=("info", "export"))
    for cut in sorted(set(int(len(base_bpm) * f) for f in (0.1, 0.25, 0.5, 0.75, 0.9, 0.99))):
        add(f"truncated to {cut} of {len(base_bpm)}", base_bpm[:cut], tools=("info", "export"))
    for i, m in enumerate(mutate_bytes(rng, base_bpm, 60)):
        add(f"mutation {i}", m, expect="any", tools=("info", "export") if i % 6 else ("info", "export", "view"))
    for sname, make in SPECIAL:
        cases.append(Case(cls, f"info: input is {sname}", ["info", "in.bpm"], {"in.bpm": make}, "refuse", "in.bpm"))
    return cases


def scene_cases(rng, base_bpm, base_obj):
    cls = "scene/bundle"
    cases = []

    def add(name, scene, extra_files=None, expect="refuse", view=True):
        data = scene if isinstance(scene, bytes) else json.dumps(scene).encode()
        files = {"src/scene.json": data, "src/m.obj": base_obj, "src/b.bpm": base_bpm}
        files.update(extra_files or {})
        cases.append(Case(cls, f"pack: {name}", ["pack", "src/scene.json", "-o", "bundle/", "--quiet"], files, expect,
                          "scene.json"))
        if view:
            cases.append(Case(cls, f"bodyview bundle: {name}",
                              ["@bodyview", "--headless", "--size", "64x48", "--frames", "2", "src/"], files,
                              "skip" if expect == "refuse" else expect, "src/"))

    good = {"version": 1, "models": [{"name": "m", "file": "m.obj"}, {"name": "b", "file": "b.bpm"}]}
    add("model file missing", {"models": [{"name": "x", "file": "nope.obj"}]})
    add("model file is a FIFO", {"models": [{"name": "x", "file": "f.obj"}]}, {"src/f.obj": fifo})
    add("model file is /dev/zero", {"models": [{"name": "x", "file": "z.bpm"}]}, {"src/z.bpm": dev_zero})
    add("model file is a directory", {"models": [{"name": "x", "file": "d.obj"}]}, {"src/d.obj": directory})
    add("model path escapes the bundle", {"models": [{"name": "x", "file": "../../../etc/passwd"}]})
    add("absolute model path", {"models": [{"name": "x", "file": "/etc/passwd"}]})
    add("models not an array", {"models": 5})
    add("no models", {"models": []})
    add("model without file", {"models": [{"name": "x"}]})
    add("unknown style", {"models": [{"name": "m", "file": "m.obj", "style": "plaid"}]})
    add("style with newline", {"models": [{"name": "m", "file": "m.obj", "style": "smooth\nrm -rf"}]})
    add("colour 50", {"models": [{"name": "m", "file": "m.obj", "colour": [50, 0, 0]}]})
    add("colour string", {"models": [{"name": "m", "file": "m.obj", "colour": "red"}]})
    add("transform NaN", json.dumps({"models": [{"name": "m", "file": "m.obj", "transform": {"translate": [1, 2, 3]}}]})
        .replace("[1, 2", "[NaN, 2", 1).encode())
    add("transform 1e308 scale", {"models": [{"name": "m", "file": "m.obj", "transform": {"scale": 1e308}}]})
    add("transform 3 values", {"models": [{"name": "m", "file": "m.obj", "transform": [1, 2, 3]}]})
    add("camera polar 500", dict(good, camera={"polar_deg": 500}))
    add("camera fov 0", dict(good, camera={"fov_deg": 0}))
    add("group unknown", {"models": [{"name": "m", "file": "m.obj", "group": "nowhere"}]})
    add("reset before idle", dict(good, kiosk={"idle_seconds": 60, "reset_seconds": 1}))
    add("tour of nothing", dict(good, tours=[{"name": "t", "steps": []}]))
    add("pin anchor NaN-ish", {"models": [{"name": "m", "file": "m.obj", "pins": [{"anchor": [1e400, 0, 0]}]}]})
    add("lod 7", {"models": [{"name": "m", "file": "m.obj", "lod": 7}]})
    add("duplicate names", {"models": [{"name": "m", "file": "m.obj"}, {"name": "m", "file": "m.obj"}]}, expect="any")
    add("name with control characters", {"models": [{"name": "m\x1b[2J\x07", "file": "m.obj"}]}, expect="any")
    add("unknown key", dict(good, colour_sceme=1))
    add("version 99", dict(good, version=99))
    add("empty file", b"")
    add("not JSON", b"models: [m.obj]\n")
    add("deep nesting", b"[" * 100000 + b"]" * 100000)
    add("a bad model among good", {"models": [{"name": "m", "file": "m.obj"}, {"name": "bad", "file": "bad.bpm"}]},
        {"src/bad.bpm": base_bpm[:len(base_bpm) // 2]})
    add("every model bad", {"models": [{"name": "bad", "file": "bad.bpm"}]}, {"src/bad.bpm": b"BPM garbage"})
    many = {"models": [{"name": f"m{i}", "file": "b.bpm"} for i in range(2000)]}
    add("2000 models", many, expect="any", view=False)
    # The kiosk on 10,000 models (one loader thread each once needed 4.2 GB): bounded, no crash.
    cases.append(Case(cls, "bodyview bundle: 10000 models",
                      ["@bodyview", "--headless", "--size", "64x48", "--frames", "2", "src/"],
                      {"src/scene.json": json.dumps({"models": [{"name": f"m{i}", "file": "b.bpm"}
                                                                for i in range(10000)]}).encode(),
                       "src/b.bpm": base_bpm}, "any", "src/", slow=True))
    for i, m in enumerate(mutate_bytes(rng, json.dumps(good).encode(), 24)):
        add(f"mutation {i}", m, expect="any", view=i % 4 == 0)
    # A bundle with a FIFO in place of a model: the kiosk must not block.
    cases.append(Case(cls, "bodyview screenshot: bundle model is a FIFO",
                      ["@bodyview", "--headless", "--size", "64x48", "--scene", "src/scene.json", "--screenshot",
                       "out.png"],
                      {"src/scene.json": json.dumps({"models": [{"name": "x", "file": "f.bpm"}]}).encode(),
                       "src/f.bpm": fifo}, "fail", "f.bpm"))
    cases.append(Case(cls, "bodyview screenshot: every model bad",
                      ["@bodyview", "--headless", "--size", "64x48", "--scene", "src/scene.json", "--screenshot",
                       "out.png"],
                      {"src/scene.json": json.dumps({"models": [{"name": "x", "file": "x.bpm"}]}).encode(),
                       "src/x.bpm": b"garbage"}, "fail", "x.bpm"))
    return cases


def output_cases(base_obj, base_bpm):
    cls = "output path"
    cases = []
    stk = json.dumps(good_stack()).encode()
    ins = {"in.contours.json": stk, "in.obj": base_obj}
    C = lambda name, argv, expect="fail", needle=None, files=None: cases.append(  # noqa: E731
        Case(cls, name, argv, files or ins, expect, needle))
    C("build -o equal to input", ["build", "in.contours.json", "-o", "in.contours.json"], needle="in.contours.json")
    C("build -o a link to the input", ["build", "in.contours.json", "-o", "link.obj"], needle="link.obj",
      files=dict(ins, **{"link.obj": lambda p: os.symlink("in.contours.json", p)}))
    C("lod -o equal to input", ["lod", "in.obj", "-o", "in.obj"], needle="in.obj")
    C("export -o equal to input", ["export", "in.obj", "-o", "in.obj"], needle="in.obj")
    C("build -o into a missing directory", ["build", "in.contours.json", "-o", "no/such/dir/out.obj"], needle="no/such")
    C("build -o /dev/full", ["build", "in.contours.json", "-o", "/dev/full"], needle="/dev/full")
    C("build -o an existing directory as a file", ["build", "in.contours.json", "-o", "d.obj"], "any",
      needle="d.obj", files=dict(ins, **{"d.obj": directory}))  # an existing directory is a directory output
    C("build -o a FIFO", ["build", "in.contours.json", "-o", "f.obj"], needle="f.obj",
      files=dict(ins, **{"f.obj": fifo}))
    C("build -o unknown extension", ["build", "in.contours.json", "-o", "out.xyz"], needle="out.xyz")
    C("build -o .stl", ["build", "in.contours.json", "-o", "out.stl"], needle="out.stl")
    C("build -o empty", ["build", "in.contours.json", "-o", ""], needle="-o")
    C("build -o a 300-byte name", ["build", "in.contours.json", "-o", "x" * 300 + ".obj"], needle="xxxx")
    C("build -o /proc/version", ["build", "in.contours.json", "-o", "/proc/version"], needle="/proc/version")
    C("build without -o", ["build", "in.contours.json"], needle="-o")
    C("lod -o unknown extension", ["lod", "in.obj", "-o", "out.txt"], needle="out.txt")
    C("pack -o a file", ["pack", "s/scene.json", "-o", "in.obj"], needle="in.obj",
      files=dict(ins, **{"s/scene.json": b'{"models": [{"name": "m", "file": "m.obj"}]}', "s/m.obj": base_obj}))
    C("pack -o a non-bundle directory", ["pack", "s/scene.json", "-o", "notbundle/"], needle="notbundle",
      files=dict(ins, **{"s/scene.json": b'{"models": [{"name": "m", "file": "m.obj"}]}', "s/m.obj": base_obj,
                         "notbundle/keep.txt": b"precious\n"}))
    C("pack -o its own source directory", ["pack", "s/scene.json", "-o", "s/"], needle="s",
      files=dict(ins, **{"s/scene.json": b'{"models": [{"name": "m", "file": "m.obj"}]}', "s/m.obj": base_obj}))
    C("exhibit -o a non-bundle directory", ["exhibit", "in.obj", "-o", "notbundle/"], needle="notbundle",
      files=dict(ins, **{"notbundle/keep.txt": b"precious\n"}))
    C("contours -o equal to input", ["contours", "in.nii", "-o", "in.nii"], needle="in.nii",
      files={"in.nii": nifti()})
    C("export -o unknown format", ["export", "in.obj", "-o", "out.fbx"], needle="out.fbx")
    C("extract -o equal to input", ["extract", "in.bpm", "--ratio", "0.5", "-o", "in.bpm"], needle="in.bpm",
      files=dict(ins, **{"in.bpm": base_bpm}))
    C("bodyview --screenshot into a missing directory",
      ["@bodyview", "--headless", "--size", "64x48", "--model", "in.obj", "--screenshot", "no/dir/x.png"],
      needle="no/dir/x.png")
    C("bodyview --screenshot equal to the model",
      ["@bodyview", "--headless", "--size", "64x48", "--model", "in.obj", "--screenshot", "in.obj"], needle="in.obj")
    return cases


def flag_cases(base_obj):
    cls = "bodyview flags"
    cases = []
    files = {"m.obj": base_obj, "r/replay.txt": b"size 64 48\n0.0 down 1 10 10\n0.1 up 1 10 10\n"}
    base = ["@bodyview", "--headless"]
    flags = [
        ("--size", "16384x16384"), ("--size", "0x0"), ("--size", "-5x10"), ("--size", "abc"), ("--size", "64"),
        ("--size", "99999999999x2"), ("--frames", "0"), ("--frames", "-1"), ("--frames", "x"),
        ("--frames", "99999999999999999999"), ("--lod", "0"), ("--lod", "2"), ("--lod", "nan"), ("--lod", "-1"),
        ("--line-width", "-3"), ("--line-width", "nan"), ("--line-width", "1e9"), ("--style", "plaid"),
        ("--select", "nobody"), ("--view", "1,2,3"), ("--view", "nan,0"), ("--view", "x"), ("--ssaa", "0"),
        ("--ssaa", "100"), ("--ssaa", "-1"), ("--rotate", "45"), ("--rotate", "x"), ("--buffer-access", "magic"),
        ("--replay", "r"), ("--replay", "nope.txt"), ("--replay", "/dev/zero"), ("--platform", "vulkan"),
        ("--mode", "x"), ("--touch-calibration", "1 2 3"), ("--touch-calibration", "a b c d e f"),
        ("--display-width-mm", "-1"), ("--display-width-mm", "nan"), ("--log-level", "loud"), ("--soak", "-1"),
        ("--soak", "x"), ("--bench-triangles", "-1"), ("--bench-frames", "0"), ("--config", "nope.conf"),
        ("--config", "r"), ("--scene", "r"), ("--model", "r"), ("--model", "nope.bpm"), ("--contours", "nope.json"),
        ("--unknown-flag", None), ("--size", None), ("--frames", None), ("--model", None),
    ]
    for flag, value in flags:
        argv = base + ["--size", "64x48"] if flag != "--size" else list(base)
        argv = argv + [flag] + ([value] if value is not None else [])
        if flag not in ("--model", "--scene", "--contours"):
            argv += ["--model", "m.obj"]
        if flag in ("--replay", "--frames", "--rotate", "--touch-calibration", "--display-width-mm", "--soak",
                    "--bench-triangles", "--bench-frames", "--log-level", "--config", "--mode", "--platform"):
            argv += ["--frames", "2"] if flag not in ("--frames",) else []
        else:
            argv += ["--screenshot", "out.png"]
        needle = flag if value is None or value in ("r", "nope.txt", "/dev/zero", "nope.conf", "nope.bpm",
                                                     "nope.json") else flag
        if value in ("nope.txt", "nope.conf", "nope.bpm", "nope.json", "/dev/zero"):
            needle = value
        elif value == "r":
            needle = "r"
        cases.append(Case(cls, f"{flag} {value}", argv, files, "refuse", needle))
    # A replay whose end is far away, and garbage replays.
    for name, body in (("end 1e9 s", b"size 64 48\n1000000000 end\n"), ("binary", bytes(range(256)) * 4),
                       ("event type with newline", b"size 64 48\n0.0 do\x1bwn 1 1 1\n"),
                       ("negative time", b"size 64 48\n-5 down 1 1 1\n"),
                       ("size 0 0", b"size 0 0\n0 end\n")):
        cases.append(Case(cls, f"--replay {name}",
                          base + ["--size", "64x48", "--model", "m.obj", "--replay", "bad.txt"],
                          dict(files, **{"bad.txt": body}), "refuse", "bad.txt"))
    return cases


def big_stack():
    """A stack whose build writes a few MB: long enough to be interrupted."""
    return json.dumps(stack([{"z": z, "contours": [{"structure": "a", "points": circle(3000, 50 + 5 * math.sin(z))}]}
                             for z in range(0, 80, 2)])).encode()


def interrupt_cases():
    """(name, argv, output, signal): a write interrupted once its temporary
    exists. SIGINT/SIGTERM must leave nothing; after SIGKILL the next write to
    the same output must sweep what the killed one left. An older output must
    survive either way."""
    runs = [("build -o FILE", ["build", "big.contours.json", "-o", "out.obj", "--quiet"], "out.obj"),
            ("build -o DIR/", ["build", "big.contours.json", "-o", "outdir/", "--quiet"], "outdir"),
            ("lod -o FILE", ["lod", "big.obj", "-o", "out.bpm", "--quiet"], "out.bpm"),
            ("exhibit -o BUNDLE/", ["exhibit", "big.obj", "-o", "bundle/", "--quiet"], "bundle")]
    return [(f"{name} {sig.name}", argv, out, sig) for name, argv, out in runs
            for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGKILL)]


def run_interrupt(spec, bins, work, big_obj):
    name, argv, output, sig = spec
    make_files(work, {"big.contours.json": big_stack(), "big.obj": big_obj})
    # An older output that must survive: the same command run to its end first.
    subprocess.run([bins["bodygen"]] + argv, cwd=work, check=True, stdout=subprocess.DEVNULL)
    before = snapshot(work)
    t0 = time.monotonic()
    proc = subprocess.Popen([bins["bodygen"]] + argv, cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            preexec_fn=limits)
    caught = False
    while proc.poll() is None and time.monotonic() - t0 < TIME_LIMIT:
        if any(".tmp-" in e for e in os.listdir(work)):
            proc.send_signal(sig)
            caught = True
            break
        time.sleep(0.0005)
    try:
        proc.communicate(timeout=TIME_LIMIT)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.communicate()
    problems = []
    if not caught:
        problems.append("missed (the write ended before its temporary was seen)")
    elif proc.returncode != -sig:
        problems.append(f"exit {proc.returncode} (expected death by {sig.name})")
    after = snapshot(work)
    if any(before.get(k) != v for k, v in after.items() if k in before) or any(k not in after for k in before):
        problems.append("destroyed")
    new = sorted(k for k in after if k not in before)
    if sig == signal.SIGKILL:
        # The next write to the same output sweeps the dead process's temporaries.
        subprocess.run([bins["bodygen"]] + argv, cwd=work, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        new = sorted(k for k in snapshot(work) if k not in before)
    if new:
        problems.append("leftover " + ",".join(new[:3]))
    return {"class": "interrupted write", "name": name, "argv": " ".join(argv), "rc": proc.returncode,
            "seconds": round(time.monotonic() - t0, 2), "stderr": [], "problems": problems}


# ------------------------------------------------------------ running

def make_files(work, files):
    for name, content in files.items():
        path = os.path.join(work, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        if callable(content):
            content(path)
        else:
            with open(path, "wb") as f:
                f.write(content)


def snapshot(work):
    """path -> digest of every entry under work (special files by type)."""
    out = {}
    for dirpath, dirnames, filenames in os.walk(work):
        for name in dirnames + filenames:
            p = os.path.join(dirpath, name)
            rel = os.path.relpath(p, work)
            st = os.lstat(p)
            if stat.S_ISREG(st.st_mode):
                with open(p, "rb") as f:
                    out[rel] = hashlib.md5(f.read()).hexdigest()
            elif stat.S_ISDIR(st.st_mode):
                out[rel] = "dir"
            else:
                out[rel] = "special"
    return out


def limits():
    if AS_LIMIT:
        resource.setrlimit(resource.RLIMIT_AS, (AS_LIMIT, AS_LIMIT))
    os.setsid()


def run_case(case, bins, work):
    make_files(work, case.files)
    before = snapshot(work)
    argv = list(case.argv)
    tool = "bodyview" if argv[0] == "@bodyview" else "bodygen"
    if argv[0] == "@bodyview":
        argv = argv[1:]
    cmd = [bins[tool]] + argv
    t0 = time.monotonic()
    proc = subprocess.Popen(cmd, cwd=work, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            preexec_fn=limits)
    try:
        out, err = proc.communicate(timeout=TIME_LIMIT)
        hung = False
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        out, err = proc.communicate()
        hung = True
    seconds = time.monotonic() - t0
    after = snapshot(work)
    rc = proc.returncode
    lines = [l for l in err.decode("utf-8", "replace").splitlines() if l.strip()]
    problems = []
    if hung:
        problems.append("hang")
    elif rc < 0:
        problems.append(f"crash (signal {-rc})")
    if any(before.get(k) != v for k, v in after.items() if k in before) or any(k not in after for k in before):
        problems.append("destroyed")
    new = sorted(k for k in after if k not in before)
    if not hung and rc > 0 and new:
        problems.append("leftover " + ",".join(new[:3]))
    if not hung and rc >= 0:
        located = len(lines) == 1 and (case.needle is None or case.needle in lines[0])
        if case.expect == "refuse":
            if rc == 0:
                problems.append("accepted")
            elif rc != 2 or not located:
                problems.append("message")
        elif case.expect == "fail":
            if rc == 0:
                problems.append("accepted")
            elif rc not in (1, 2) or not located:
                problems.append("message")
        elif case.expect == "skip":
            if not any(case.needle is None or case.needle in l for l in lines) and rc != 0:
                problems.append("message")
            elif rc == 0 and not lines:
                problems.append("accepted")
        elif case.expect == "any" and rc not in (0, 1, 2):
            problems.append(f"exit {rc}")
    return {"class": case.cls, "name": case.name, "argv": " ".join(case.argv), "rc": rc, "seconds": round(seconds, 2),
            "stderr": lines[:3], "problems": problems}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--only")
    ap.add_argument("--keep", action="store_true")
    ap.add_argument("--json")
    ap.add_argument("-v", action="store_true")
    args = ap.parse_args()
    bins = {t: os.path.join(os.path.abspath(args.build), "bin", t) for t in ("bodygen", "bodyview")}
    for t, p in bins.items():
        if not os.access(p, os.X_OK):
            print(f"hostile_sweep: {p} missing")
            return 1
    # Sanitizer builds reserve terabytes of shadow address space: there the
    # address-space limit cannot apply (said once, and the rest runs).
    global AS_LIMIT
    probe = subprocess.run([bins["bodygen"], "--version"], capture_output=True, preexec_fn=limits)
    if probe.returncode != 0:
        print("hostile_sweep: bodygen does not start under a 4 GiB address-space limit (a sanitizer build?): "
              "running without it")
        AS_LIMIT = 0
    top = tempfile.mkdtemp(prefix="body_sweep_")
    try:
        base_obj = open(os.path.join(ROOT, "tests/data/models/smoke.obj"), "rb").read()
        subprocess.run([bins["bodygen"], "lod", os.path.join(ROOT, "tests/data/models/smoke.obj"), "-o",
                        os.path.join(top, "base.bpm"), "--quiet"], check=True)
        base_bpm = open(os.path.join(top, "base.bpm"), "rb").read()
        rng = random.Random(30)
        cases = (contour_cases(rng) + nifti_cases(rng) + rtstruct_cases(rng) + mesh_cases(rng) +
                 bpm_cases(rng, base_bpm) + scene_cases(rng, base_bpm, base_obj) + output_cases(base_obj, base_bpm) +
                 flag_cases(base_obj) + gltf_cases(rng))
        if args.only:
            cases = [c for c in cases if args.only.lower() in c.cls.lower()]
        if args.quick:
            by_class = collections.defaultdict(list)
            for c in cases:
                by_class[c.cls].append(c)
            cases = [c for cs in by_class.values() for c in [c for c in cs if not c.slow][::9]]
        results = []
        for i, case in enumerate(cases):
            work = os.path.join(top, f"case{i}")
            os.mkdir(work)
            r = run_case(case, bins, work)
            results.append(r)
            if r["problems"] or args.v:
                print(f"[{r['class']}] {r['name']}: exit {r['rc']} in {r['seconds']} s: "
                      f"{', '.join(r['problems']) or 'ok'}: {' | '.join(r['stderr'])[:300]}", flush=True)
            if not args.keep:
                for dirpath, dirnames, _ in os.walk(work):
                    for d in dirnames:
                        os.chmod(os.path.join(dirpath, d), 0o755)
                shutil.rmtree(work, ignore_errors=True)
        interrupts = interrupt_cases()
        big_obj = b""
        if interrupts:  # a mesh of a few MB for lod and exhibit to write
            with open(os.path.join(top, "big.contours.json"), "wb") as f:
                f.write(big_stack())
            subprocess.run([bins["bodygen"], "build", "big.contours.json", "-o", "big.obj", "--quiet"], cwd=top,
                           check=True)
            big_obj = open(os.path.join(top, "big.obj"), "rb").read()
        if args.only:
            interrupts = [i for i in interrupts if args.only.lower() in "interrupted write"]
        if args.quick:
            interrupts = [i for i in interrupts if i[0].startswith(("build -o DIR/", "exhibit"))][::2]
        for i, spec in enumerate(interrupts):
            work = os.path.join(top, f"interrupt{i}")
            os.mkdir(work)
            r = run_interrupt(spec, bins, work, big_obj)
            results.append(r)
            if r["problems"] or args.v:
                print(f"[{r['class']}] {r['name']}: exit {r['rc']} in {r['seconds']} s: "
                      f"{', '.join(r['problems']) or 'ok'}", flush=True)
            if not args.keep:
                shutil.rmtree(work, ignore_errors=True)
        table = collections.OrderedDict()
        for r in results:
            row = table.setdefault(r["class"], collections.Counter())
            row["cases"] += 1
            for p in r["problems"]:
                row[p.split(" ")[0]] += 1
        kinds = ["crash", "hang", "leftover", "destroyed", "accepted", "message", "exit", "missed"]
        print("\n| class | cases | " + " | ".join(kinds) + " |")
        print("|---|---|" + "---|" * len(kinds))
        total = collections.Counter()
        for cls, row in table.items():
            total.update(row)
            print(f"| {cls} | {row['cases']} | " + " | ".join(str(row[k]) for k in kinds) + " |")
        print(f"| all | {total['cases']} | " + " | ".join(str(total[k]) for k in kinds) + " |")
        slowest = sorted(results, key=lambda r: -r["seconds"])[:3]
        print("slowest: " + ", ".join(f"{r['name']} {r['seconds']} s" for r in slowest))
        if args.json:
            with open(args.json, "w") as f:
                json.dump(results, f, indent=1)
        # A missed interruption (the write ended first) proves nothing either way: reported, not failed.
        failed = sum(1 for r in results if any(not p.startswith("missed") for p in r["problems"]))
        print(f"hostile_sweep: {len(results)} cases, {failed} with a problem")
        return 0 if failed == 0 else 1
    finally:
        if not args.keep:
            shutil.rmtree(top, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
