#!/usr/bin/env python3
# Estimates what other codings of a .bpm's split positions would cost, from a dump
# of the writer's per-split values, without writing a reader for each (bench/RESULTS.md,
# issue 24, seventeenth session). Each value costs its symbol at the order-0 entropy
# of its context over the whole file plus its raw bits, as pm::SplitEncoder splits
# values (--sizes uses per-chunk tables: this matched it to 0.005 B per split).
#
# usage: git apply bench/split_estimate_dump.patch && cmake --build build --target bodygen
#        BPM_DUMP=bunny.dump build/bin/bodygen lod bunny.obj -o bunny.bpm --sizes
#        git apply -R bench/split_estimate_dump.patch     (the dump is scratch, never committed applied)
#        /usr/bin/python3 bench/split_estimate.py bunny.dump
# The dump: 64 int64 per split (see the patch): fan, moves, grids, the parent's codes
# before/after (decoded and builder's), the child's, the predictions of prediction.h,
# the plane, the coded values and shifts. The script first re-derives the dumped
# values with the format's predictions (a check that it codes what the writer does),
# then prices the variants (version 6's prediction among them).
import sys

import numpy as np

FIRST = np.array([1, 0, 0, 0])
SECOND = np.array([2, 2, 1, 1])


def symbols(v):
    """pm::value_symbol: the symbol and its raw bits of each value."""
    v = np.asarray(v, np.int64)
    n = np.where(v < 8, 0, np.floor(np.log2(np.maximum(v, 1))).astype(np.int64) + 1)
    bits = np.where(v < 8, 0, n - 2)
    sym = np.where(v < 8, v, 8 + (n - 4) * 2 + ((v >> np.maximum(bits, 0)) & 1))
    return sym, bits


def cost(values, shifts, ctx=None):
    """Bits: the symbols of values >> shifts at their order-0 entropy per context, plus the raw bits."""
    values = np.asarray(values, np.int64)
    shifts = np.broadcast_to(np.asarray(shifts, np.int64), values.shape)
    if len(values) == 0:
        return 0.0
    s, b = symbols(values >> shifts)
    ctx = np.zeros(len(values), np.int64) if ctx is None else np.asarray(ctx, np.int64)
    _, counts = np.unique(ctx * 100 + s, return_counts=True)
    _, per_ctx = np.unique(ctx, return_counts=True)
    return float(-(counts * np.log2(counts)).sum() + (per_ctx * np.log2(per_ctx)).sum() + b.sum() + shifts.sum())


def zz(r):
    r = np.asarray(r, np.int64)
    return np.where(r >= 0, 2 * r, -2 * r - 1)


def wrap16(x):
    x = np.asarray(x, np.int64) & 0xFFFF
    return np.where(x >= 32768, x - 65536, x)


def take(a, idx):
    return np.take_along_axis(a, idx[:, None], 1)[:, 0]


def round_div(a, b):
    sgn = np.where(b < 0, -1, 1)
    a, b = a * sgn, b * sgn
    b = np.where(b == 0, 1, b)
    return np.floor_divide(2 * a + b, 2 * b)


class Splits:
    def __init__(self, path):
        r = np.fromfile(path, dtype=np.int64).reshape(-1, 64)
        self.n = len(r)
        self.fan, self.moves = r[:, 0] == 1, r[:, 1] == 1
        self.cg, self.pg = r[:, 2], r[:, 3]
        self.frm, self.to, self.to_t, self.at_t, self.at = (r[:, i : i + 3] for i in (4, 7, 10, 13, 16))
        self.pchild, self.pcent, self.shift, self.normal = (r[:, i : i + 3] for i in (19, 22, 25, 28))
        self.axis, self.ashift, self.cdot, self.pdot = r[:, 37], r[:, 38], r[:, 39], r[:, 40]
        self.val, self.shv = r[:, 41:47], r[:, 47:53]
        self.plane = self.axis < 3
        self.order = np.stack(
            [np.where(self.plane, FIRST[np.minimum(self.axis, 3)], 0),
             np.where(self.plane, SECOND[np.minimum(self.axis, 3)], 1),
             np.where(self.plane, self.axis, 2)], 1)

    def plane_coord(self, t, offset, scale):
        a, b, ax = self.order[:, 0], self.order[:, 1], np.minimum(self.axis, 2)
        along = take(self.normal, a) * (take(t, a) - take(self.frm, a)) + take(self.normal, b) * (
            take(t, b) - take(self.frm, b))
        return (take(self.frm, ax) + round_div(offset - scale * along, scale * take(self.normal, ax))) & 0xFFFF


def code(s, target, pred, grid, shift01, plane_offset, plane_scale, plane_shift):
    """One position per split on its grid as the writer codes it: values, shifts, decoded codes."""
    val = np.zeros((s.n, 3), np.int64)
    sh = np.zeros((s.n, 3), np.int64)
    out = np.zeros((s.n, 3), np.int64)
    for i in range(3):
        k = s.order[:, i]
        pr, sc = take(pred, k), take(shift01, k)
        if i == 2:
            pr = np.where(s.plane, s.plane_coord(out, plane_offset, plane_scale), pr)
            sc = np.where(s.plane, plane_shift, sc)
        r = wrap16(take(target, k) - pr)
        rounded = (r + np.where(grid > 0, 1 << np.maximum(grid - 1, 0), 0)) >> grid
        val[:, i] = zz(rounded)
        sh[:, i] = np.maximum(sc - grid, 0)
        np.put_along_axis(out, k[:, None], (take(target, k) + (rounded << grid) - r)[:, None], 1)
    return val, sh, out


def parent_pred(s, a8):
    """v + a8/8 (v - c) + (C_p - v)/2 (a8 = 1: version 7), or None: version 6's midpoint(2v - c, C_p)."""
    refl = (2 * s.frm - s.at) & 0xFFFF
    if a8 is None:
        return np.where(s.fan[:, None], (refl + s.pcent + 1) // 2, refl)
    return np.where(s.fan[:, None], (((4 + a8) * s.frm - a8 * s.at + 4 * s.pcent + 4) >> 3) & 0xFFFF, refl)


def parent_bits(s, a8, v7_plane, more01, less2):
    """The parent move's bits per axis: prediction a8 (parent_pred), version 7's plane offset or 6's, the
    in-plane shifts `more01` above the dump's (version 7's), the plane axis' `less2` below the ring's."""
    dot = (s.normal * (s.at - s.frm)).sum(1)
    off, sc = (2 * s.pdot - 4 * dot, 64) if v7_plane else (s.pdot - 4 * dot, 8)
    val, sh, _ = code(s, s.to_t, parent_pred(s, a8), s.pg, s.shift + more01, np.where(s.plane, off, 0), sc,
                      np.maximum(s.ashift - less2, 0))
    m = s.moves
    return [cost(val[m, i], sh[m, i]) / 8 / s.n for i in range(3)]


def unit(v):
    length = np.linalg.norm(v, axis=1, keepdims=True)
    return v / np.where(length > 0, length, 1)


def frame_bits(s, sel, residual, e, grid):
    """Candidates (a) and (b): a residual coded in a local frame (e, the normal orthogonal to e, their
    cross product), each component rounded on the grid (an ideal rotated lattice: an exact integer
    scheme costs more), each with its own context and the ring's largest shift less 0-5 (the best)."""
    nrm = s.normal[sel].astype(float)
    nn = unit(nrm - (nrm * e).sum(1, keepdims=True) * e)
    out = []
    for axis in (e, nn, np.cross(nn, e)):
        q = zz(np.round((residual * axis).sum(1) / (1 << grid)).astype(np.int64))
        out.append(min(cost(q, np.maximum(s.shift[sel].max(1) - d - grid, 0)) for d in range(6)) / 8 / s.n)
    return out


def main():
    s = Splits(sys.argv[1])  # a dump of version 7's writer
    # The check: the dumped values are what this script codes.
    val, sh, _ = code(s, s.at_t, s.pchild, s.cg, s.shift, s.cdot, 4, s.ashift)
    print("child values as dumped:", bool((val == s.val[:, :3]).all() and (sh == s.shv[:, :3]).all()))
    dot = (s.normal * (s.at - s.frm)).sum(1)
    pv, ps, _ = code(s, s.to_t, parent_pred(s, 1), s.pg, s.shift, np.where(s.plane, 2 * s.pdot - 4 * dot, 0), 64,
                     np.maximum(s.ashift - 1, 0))
    m = s.moves
    print("parent values as dumped:", bool((pv[m] == s.val[m, 3:]).all() and (ps[m] == s.shv[m, 3:]).all()))
    child = [cost(s.val[:, i], s.shv[:, i]) / 8 / s.n for i in range(3)]
    parent = [cost(s.val[m, 3 + i], s.shv[m, 3 + i]) / 8 / s.n for i in range(3)]
    print("as written: child %.3f (%s), parent move %.3f (%s) B per split" % (
        sum(child), " ".join("%.3f" % x for x in child), sum(parent), " ".join("%.3f" % x for x in parent)))
    val6, sh6, _ = code(s, s.at_t, s.pchild, s.cg, s.shift + 1, s.cdot, 4, s.ashift)
    print("child with version 6's shifts (one more): %.3f" % (sum(cost(val6[:, i], sh6[:, i]) for i in range(3)) / 8 / s.n))
    print("parent move variants (in-plane axes 0, 1, the plane's axis; B per split):")
    for name, a8, v7p, more01, less2 in [
            ("v6: midpoint(2v - c, C_p); plane N.(C_p - v)/8 - N.(c - v)/2", None, False, 1, 0),
            ("v6 prediction, v7 shifts", None, False, 0, 1),
            ("v7: v + (v - c)/8 + (C_p - v)/2; plane N.(C_p - v)/32 - N.(c - v)/16", 1, True, 0, 1),
            ("v7, plane offset v6's", 1, False, 0, 1),
            ("v + (C_p - v)/2 (no child)", 0, True, 0, 1),
            ("v + (v - c)/4 + (C_p - v)/2", 2, True, 0, 1),
            ("v7, plane axis shift as the child's", 1, True, 0, 0),
            ("v7, plane axis shift two less", 1, True, 0, 2)]:
        b = parent_bits(s, a8, v7p, more01, less2)
        print("  %-72s %.3f (%s)" % (name, sum(b), " ".join("%.3f" % x for x in b)))
    f = s.moves & s.fan & s.plane
    v, c = s.frm[f].astype(float), s.at[f].astype(float)
    b = frame_bits(s, f, s.to_t[f] - (2 * v - c), unit(v - c), s.pg[f])
    print("(a) parent move - reflection 2v - c, frame along the edge c -> v, the normal, the rest: %.3f (%s)" % (
        sum(b), " ".join("%.3f" % x for x in b)))
    b = frame_bits(s, f, s.to_t[f] - v, unit(v - c), s.pg[f])
    print("(a) parent move - v, the same frame: %.3f (%s)" % (sum(b), " ".join("%.3f" % x for x in b)))
    b = frame_bits(s, f, s.to_t[f] - parent_pred(s, 1)[f], unit(v - c), s.pg[f])
    print("(a) parent move - version 7's prediction, the same frame: %.3f (%s)" % (sum(b), " ".join("%.3f" % x for x in b)))
    cc = 2 * s.pchild[f].astype(float) - v
    b = frame_bits(s, f, s.at_t[f] - s.pchild[f], unit(cc - v), s.cg[f])
    print("(b) child - midpoint(v, C_c), frame along v -> C_c, the normal, the rest: %.3f (%s) (as written on the "
          "same splits: %.3f)" % (sum(b), " ".join("%.3f" % x for x in b),
                                  sum(cost(s.val[f, i], s.shv[f, i]) for i in range(3)) / 8 / s.n))
    print("contexts (child / parent move, B per split; each context's own table, not counted):")
    for name, cc, pc in [("none", None, None), ("grid", np.minimum(s.cg, 6), np.minimum(s.pg, 6)),
                         ("ring shift", np.minimum(s.shift.max(1), 12), np.minimum(s.shift.max(1), 12))]:
        c = sum(cost(s.val[:, i], s.shv[:, i], cc) for i in range(3)) / 8 / s.n
        p = sum(cost(s.val[m, 3 + i], s.shv[m, 3 + i], None if pc is None else pc[m]) for i in range(3)) / 8 / s.n
        print("  %-12s %.3f / %.3f" % (name, c, p))


if __name__ == "__main__":
    main()
