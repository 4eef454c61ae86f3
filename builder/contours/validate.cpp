// Contour validation and repair (the contract is in validate.h): per contour
// finiteness, point clean-up, degenerate contours and keyhole cuts; per slice
// the crossings (crossings.cpp), repaired by union (repair.cpp); even-odd nesting.
//
// References:
//   W. R. Franklin, "PNPOLY - point inclusion in polygon test" (even-odd rule).
#include "builder/contours/validate.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "builder/contours/repair.h"
#include "shared/union_find.h"

namespace body {
namespace {

std::string where(const std::string& path, const Contour& c) {
    return path + ": slice " + std::to_string(c.source_slice) + " contour " + std::to_string(c.source_contour);
}

std::string format_point(const Vec2& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.9g, %.9g)", p.x, p.y);
    return buf;
}

double extent_of(std::span<const Vec2> pts) {
    Vec2 lo(1e300), hi(-1e300);
    for (const Vec2& p : pts) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return pts.empty() ? 0.0 : glm::length(hi - lo);
}

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

bool collinear(std::span<const Vec2> pts) {
    size_t far = 0;
    for (size_t i = 1; i < pts.size(); ++i)
        if (glm::length(pts[i] - pts[0]) > glm::length(pts[far] - pts[0])) far = i;
    const double len = glm::length(pts[far] - pts[0]);
    for (const Vec2& p : pts)
        if (std::abs(orient(pts[0], pts[far], p)) > 1e-12 * len * len) return false;
    return true;
}

size_t count_distinct(std::span<const Vec2> pts) {
    std::vector<Vec2> s(pts.begin(), pts.end());
    std::sort(s.begin(), s.end(), [](const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    return size_t(std::unique(s.begin(), s.end()) - s.begin());
}

void split_recursive(std::vector<Vec2> loop, std::vector<std::vector<Vec2>>& out, double extent) {
    const size_t n = loop.size();
    if (n < 3) return;
    std::vector<uint32_t> order(n);
    for (uint32_t i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const Vec2 &p = loop[a], &q = loop[b];
        return p.x < q.x || (p.x == q.x && (p.y < q.y || (p.y == q.y && a < b)));
    });
    for (size_t k = 0; k + 1 < n; ++k) {
        if (loop[order[k]] != loop[order[k + 1]]) continue;
        size_t i = std::min(order[k], order[k + 1]), j = std::max(order[k], order[k + 1]);
        std::vector<Vec2> first(loop.begin() + long(i), loop.begin() + long(j));
        std::vector<Vec2> second(loop.begin() + long(j), loop.end());
        second.insert(second.end(), loop.begin(), loop.begin() + long(i));
        split_recursive(std::move(first), out, extent);
        split_recursive(std::move(second), out, extent);
        return;
    }
    if (std::abs(signed_area2(loop.data(), n)) <= 1e-12 * extent * extent) return;
    out.push_back(std::move(loop));
}

}  // namespace

bool point_in_polygon(const Vec2& p, std::span<const Vec2> poly) {
    bool inside = false;
    for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const Vec2 &a = poly[i], &b = poly[j];
        if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
    }
    return inside;
}

std::vector<std::vector<Vec2>> split_keyholes(std::span<const Vec2> points) {
    std::vector<std::vector<Vec2>> out;
    split_recursive(std::vector<Vec2>(points.begin(), points.end()), out, extent_of(points));
    return out;
}

Nesting compute_nesting(std::span<const std::span<const Vec2>> contours) {
    const size_t k = contours.size();
    Nesting n;
    n.parent.assign(k, -1);
    n.depth.assign(k, 0);
    std::vector<Vec2> lo(k, Vec2(1e300)), hi(k, Vec2(-1e300));
    for (size_t i = 0; i < k; ++i)
        for (const Vec2& p : contours[i]) lo[i] = glm::min(lo[i], p), hi[i] = glm::max(hi[i], p);
    std::vector<std::vector<int>> containers(k);
    for (size_t i = 0; i < k; ++i) {
        if (contours[i].empty()) continue;
        const Vec2 p = contours[i][0];
        for (size_t j = 0; j < k; ++j) {
            if (j == i || contours[j].size() < 3) continue;
            if (p.x < lo[j].x || p.x > hi[j].x || p.y < lo[j].y || p.y > hi[j].y) continue;
            if (point_in_polygon(p, contours[j])) containers[i].push_back(int(j));
        }
        n.depth[i] = int(containers[i].size());
    }
    for (size_t i = 0; i < k; ++i)
        for (int j : containers[i])
            if (n.depth[size_t(j)] == n.depth[i] - 1) n.parent[i] = j;
    return n;
}

Nesting compute_nesting(const Slice& slice, std::span<const uint32_t> members) {
    std::vector<std::span<const Vec2>> loops;
    for (uint32_t c : members) loops.emplace_back(slice.contours[c].points);
    return compute_nesting(loops);
}

// ------------------------------------------------------------ validation

namespace {

struct Context {
    const std::string& path;
    const RepairOptions& options;
    RepairLog& log;
    double tolerance = 0.0;
    double noise = 0.0;  // points closer than this are one point (rounding noise)
    // Crossings between two structures: the first line and the number of slices, per pair.
    std::map<std::pair<std::string, std::string>, std::pair<std::string, size_t>> structure_overlaps;
};

std::string distance_text(double d) {
    char buf[48];
    std::snprintf(buf, sizeof buf, "%.3g", d);
    return buf;
}

void note_repair(Context& cx, const Contour& c, const char* kind, const Vec2& at, const std::string& what,
                 double moved) {
    cx.log.add(kind, where(cx.path, c) + ": at " + format_point(at) + ": " + what + ", points moved up to " +
                         distance_text(moved));
}

std::string too_far(const Context& cx, double moved) {
    return "; repairing it would move points by " + distance_text(moved) + " (more than the repair tolerance " +
           distance_text(cx.tolerance) + ")";
}

// Point clean-up of one contour (repair mode); an error when a spike is too long.
Status clean_points(Context& cx, Contour& c) {
    const CleanupResult r = clean_contour(c.points, cx.noise);
    const std::pair<const PointRepair*, const char*> kinds[] = {
        {&r.near_duplicate, "near_duplicate"}, {&r.collinear, "collinear"}, {&r.spike, "spike"}};
    for (const auto& [repair, kind] : kinds) {
        if (!repair->count) continue;
        if (repair->moved > cx.tolerance)
            return input_error(where(cx.path, c) + ": zero-width spike at " + format_point(repair->at) +
                               too_far(cx, repair->moved));
        const std::string what = std::string("removed ") + std::to_string(repair->count) +
                                 (repair == &r.spike       ? " zero-width spike tip(s)"
                                  : repair == &r.collinear ? " collinear point(s)"
                                                           : " near-duplicate point(s)");
        note_repair(cx, c, kind, repair->at, what, repair->moved);
    }
    return ok_status();
}

// Checks and repairs one contour; appends what remains of it to `out`.
Status validate_contour(Context& cx, Contour& c, std::vector<Contour>& out) {
    const bool strict = cx.options.strict;
    for (size_t k = 0; k < c.points.size(); ++k)
        if (!std::isfinite(c.points[k].x) || !std::isfinite(c.points[k].y))
            return input_error(where(cx.path, c) + ": point " + std::to_string(k) + " is not finite");
    const Vec2 first = c.points.empty() ? Vec2(0.0) : c.points[0];
    if (size_t removed = remove_duplicate_points(c.points))
        note_repair(cx, c, "duplicate", first, "removed " + std::to_string(removed) + " duplicate consecutive point(s)",
                    0.0);
    // Contours without area are refused, or dropped when no larger than the tolerance.
    bool dropped = false;
    auto degenerate = [&]() -> Status {
        const double extent = extent_of(c.points);
        const bool too_few = count_distinct(c.points) < 3;
        const bool flat =
            !too_few && (strict ? std::abs(signed_area2(c.points.data(), c.points.size())) <= 1e-12 * extent * extent
                                : collinear(c.points));
        if (!too_few && !flat) return ok_status();
        if (!strict && extent <= cx.tolerance) {
            note_repair(cx, c, "degenerate", first, "dropped a contour without area", extent);
            dropped = true;
            return ok_status();
        }
        if (too_few) return input_error(where(cx.path, c) + ": fewer than 3 distinct points");
        if (count_distinct(c.points) == c.points.size() && !collinear(c.points)) {
            const std::span<const Vec2> self[1] = {c.points};
            Crossing x = find_crossing(self);  // a figure eight has zero signed area too
            if (x.found) return input_error(where(cx.path, c) + ": self-intersects at " + format_point(x.point));
        }
        return input_error(where(cx.path, c) + ": zero area");
    };
    if (Status s = degenerate(); !s || dropped) return s;
    if (!strict) {
        if (Status s = clean_points(cx, c); !s) return s;
        if (Status s = degenerate(); !s || dropped) return s;
    }
    if (count_distinct(c.points) == c.points.size()) {
        out.push_back(std::move(c));
        return ok_status();
    }
    auto loops = split_keyholes(c.points);
    if (loops.empty()) return input_error(where(cx.path, c) + ": zero area");
    note_repair(cx, c, "keyhole", first, "keyhole cut split into " + std::to_string(loops.size()) + " contour(s)", 0.0);
    for (auto& loop : loops) {
        Contour piece = c;
        piece.points = std::move(loop);
        out.push_back(std::move(piece));
    }
    return ok_status();
}

std::string crossing_message(const std::string& path, const Contour& a, const Contour& b, const Crossing& x) {
    if (&a == &b) return where(path, a) + ": self-intersects at " + format_point(x.point);
    return where(path, a) + ": crosses slice " + std::to_string(b.source_slice) + " contour " +
           std::to_string(b.source_contour) + " at " + format_point(x.point);
}

// Replaces each cluster of crossing contours of one structure by the union of their regions.
Status repair_clusters(Context& cx, Slice& slice, const std::vector<Crossing>& same) {
    UnionFind uf(slice.contours.size());
    for (const Crossing& x : same) uf.unite(uint32_t(x.loop_a), uint32_t(x.loop_b));
    std::map<size_t, std::vector<size_t>> clusters;
    std::map<size_t, const Crossing*> first;
    for (const Crossing& x : same) {
        first.emplace(uf.find(uint32_t(x.loop_a)), &x);
    }
    for (size_t i = 0; i < slice.contours.size(); ++i)
        if (const uint32_t root = uf.find(uint32_t(i)); first.count(root)) clusters[root].push_back(i);
    std::vector<bool> replaced(slice.contours.size(), false);
    std::vector<Contour> added;
    for (const auto& [root, members] : clusters) {
        const Crossing& x = *first.at(root);
        std::vector<std::vector<Vec2>> loops;
        for (size_t i : members) loops.push_back(slice.contours[i].points);
        const RegionUnion u = union_regions(loops, cx.tolerance);
        const Contour& a = slice.contours[members[0]];
        const std::string problem = crossing_message(cx.path, slice.contours[x.loop_a], slice.contours[x.loop_b], x);
        if (!u.ok || u.loops.empty()) return input_error(problem + "; cannot be repaired");
        if (u.moved > cx.tolerance) return input_error(problem + too_far(cx, u.moved));
        std::string what;
        if (members.size() == 1)
            what = "self-intersection repaired into " + std::to_string(u.loops.size()) + " contour(s)";
        else {
            what = "union of " + std::to_string(members.size()) + " overlapping contours (";
            for (size_t k = 0; k < members.size(); ++k)
                what += (k ? ", " : "") + std::to_string(slice.contours[members[k]].source_contour);
            what += ") into " + std::to_string(u.loops.size()) + " contour(s)";
        }
        if (u.dropped) what += ", " + std::to_string(u.dropped) + " sliver(s) dropped";
        note_repair(cx, a, members.size() == 1 ? "self_intersection" : "overlap", x.point, what, u.moved);
        for (size_t i : members) replaced[i] = true;
        for (const auto& loop : u.loops) {
            Contour piece = a;
            piece.points = loop;
            added.push_back(std::move(piece));
        }
    }
    std::vector<Contour> kept;
    for (size_t i = 0; i < slice.contours.size(); ++i)
        if (!replaced[i]) kept.push_back(std::move(slice.contours[i]));
    for (Contour& c : added) kept.push_back(std::move(c));
    slice.contours = std::move(kept);
    return ok_status();
}

// Crossings on one slice: same structure -> error (strict) or union; different
// -> warning. After a union, pieces that touch at a point are pulled apart.
Status check_crossings(Context& cx, Slice& slice, int round) {
    std::vector<std::span<const Vec2>> loops;
    for (const Contour& c : slice.contours) loops.emplace_back(c.points);
    std::vector<Crossing> same;
    std::set<std::pair<std::string, std::string>> warned;
    for (const Crossing& x : find_crossings(loops)) {
        const Contour &a = slice.contours[x.loop_a], &b = slice.contours[x.loop_b];
        if (a.structure == b.structure) {
            if (cx.options.strict || round > 3)
                return input_error(crossing_message(cx.path, a, x.loop_a == x.loop_b ? a : b, x) +
                                   (round > 0 ? "; cannot be repaired" : ""));
            same.push_back(x);
        } else if (round == 0 && x.crosses && warned.insert({a.structure, b.structure}).second) {
            auto [it, first] = cx.structure_overlaps.emplace(
                std::pair{a.structure, b.structure},
                std::pair{where(cx.path, a) + ": at " + format_point(x.point) + ": structure '" + a.structure +
                              "' crosses slice " + std::to_string(b.source_slice) + " contour " +
                              std::to_string(b.source_contour) + " of structure '" + b.structure + "'",
                          size_t(0)});
            ++it->second.second;
        }
    }
    if (same.empty()) return ok_status();
    if (round == 0) {
        if (Status s = repair_clusters(cx, slice, same); !s) return s;
    } else {
        // Union pieces (strictly simple each) may share a point: separate them by a step far below the tolerance.
        for (const Crossing& x : same) {
            const double step = cx.tolerance * 1e-2;
            double moved = pull_inward(slice.contours[x.loop_a].points, x.point, step);
            if (x.loop_b != x.loop_a)
                moved = std::max(moved, pull_inward(slice.contours[x.loop_b].points, x.point, step));
            note_repair(cx, slice.contours[x.loop_a], "touching", x.point, "touching contours pulled apart", moved);
        }
    }
    return check_crossings(cx, slice, round + 1);
}

// Contours under RepairOptions::min_area, dropped with one line each.
void drop_small(Context& cx, Slice& slice) {
    std::vector<Contour> kept;
    for (Contour& c : slice.contours) {
        const double area = 0.5 * std::abs(signed_area2(c.points.data(), c.points.size()));
        if (area >= cx.options.min_area) {
            kept.push_back(std::move(c));
            continue;
        }
        cx.log.add("small", where(cx.path, c) + ": at " + format_point(c.points[0]) + ": dropped a contour of area " +
                                distance_text(area) + " (under --min-area " + distance_text(cx.options.min_area) +
                                "), points moved up to " + distance_text(extent_of(c.points)));
    }
    slice.contours = std::move(kept);
}

}  // namespace

double repair_tolerance(const ContourStack& stack, const RepairOptions& options) {
    if (options.tolerance > 0) return options.tolerance;
    Vec2 lo(1e300), hi(-1e300);
    for (const Slice& s : stack.slices)
        for (const Contour& c : s.contours)
            for (const Vec2& p : c.points)
                if (std::isfinite(p.x) && std::isfinite(p.y)) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return lo.x <= hi.x ? kDefaultRepairTolerance * glm::length(hi - lo) : 0.0;
}

Status validate_contour_stack(ContourStack& stack, const std::string& path, const RepairOptions& options,
                              RepairLog& log) {
    Context cx{path, options, log, 0.0, 0.0, {}};
    cx.tolerance = repair_tolerance(stack, options);
    cx.noise = cx.tolerance * 1e-3;
    for (Slice& slice : stack.slices) {
        std::vector<Contour> kept;
        for (Contour& c : slice.contours)
            if (Status s = validate_contour(cx, c, kept); !s) return s;
        slice.contours = std::move(kept);
        if (Status s = check_crossings(cx, slice, 0); !s) return s;
        if (options.min_area > 0) drop_small(cx, slice);
    }
    for (const auto& [pair, first] : cx.structure_overlaps)
        log.add("structure_overlap",
                first.first + " (both kept; the two cross on " + std::to_string(first.second) + " slice(s))");
    // A stack that leaves nothing to build is refused here, so that check and
    // build agree and build never writes an empty mesh file.
    size_t contours = 0;
    for (const Slice& slice : stack.slices) contours += slice.contours.size();
    if (contours == 0)
        return input_error(
            path + ": no contour to build from (" +
            (stack.slices.empty() ? std::string("no slices") : "every contour was empty or without area") + ")");
    return ok_status();
}

Status validate_contour_stack(ContourStack& stack, const std::string& path, std::vector<std::string>& warnings) {
    RepairLog log;
    Status s = validate_contour_stack(stack, path, RepairOptions{}, log);
    warnings.insert(warnings.end(), log.lines.begin(), log.lines.end());
    return s;
}

}  // namespace body
