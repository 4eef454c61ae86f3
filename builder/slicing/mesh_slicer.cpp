// Mesh slicing: plane/triangle intersection segments chained into loops.
//
// References:
// - H. Edelsbrunner, E. Mücke, "Simulation of simplicity", ACM TOG 9(1), 1990:
//   vertices on a plane are treated as lying just above it, which makes every
//   crossing well defined without moving the plane.
// - Segment chaining through shared mesh edges as in R. Minetto et al., "An
//   optimal algorithm for 3D triangle mesh slicing", CAD 92, 2017.
#include "builder/slicing/mesh_slicer.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "shared/edge_key.h"
#include "shared/mesh_intersect.h"

namespace body {

namespace {

Vec3 permuted(const Vec3& p, int axis) {
    return axis == 0 ? Vec3(p.y, p.z, p.x) : (axis == 1 ? Vec3(p.z, p.x, p.y) : p);
}

constexpr double kMergeDistance = 1e-5;  // relative to the mesh's bounding-box diagonal

struct Segment {
    uint64_t from, to;  // the mesh edges whose crossings start and end it
};

// Phase 1: one oriented segment per triangle that crosses the plane. Walking
// the triangle, the crossing of the edge that goes from above to below starts
// the segment and the one going back up ends it; for an outward-oriented mesh
// this runs counter-clockwise (seen from +z) around solid.
static void collect_segments(std::span<const Vec3> pos, std::span<const uint32_t> idx, double h,
                             std::vector<Segment>& segments, std::unordered_map<uint64_t, Vec2>& points) {
    segments.clear();
    points.clear();
    for (size_t t = 0; t + 2 < idx.size(); t += 3) {
        const uint32_t v[3] = {idx[t], idx[t + 1], idx[t + 2]};
        bool above[3];
        for (int k = 0; k < 3; ++k) above[k] = pos[v[k]].z >= h;
        if (above[0] == above[1] && above[1] == above[2]) continue;
        uint64_t down = 0, up = 0;
        for (int k = 0; k < 3; ++k) {
            uint32_t a = v[k], b = v[(k + 1) % 3];
            bool aa = above[k], ab = above[(k + 1) % 3];
            if (aa == ab) continue;
            uint64_t key = edge_key(a, b);
            (aa ? down : up) = key;
            if (!points.count(key)) {
                // Interpolate from the lower-indexed end so both triangles get the same point.
                const Vec3& p = pos[std::min(a, b)];
                const Vec3& q = pos[std::max(a, b)];
                double t01 = (h - p.z) / (q.z - p.z);
                t01 = std::clamp(t01, 0.0, 1.0);
                points.emplace(key, Vec2(p.x + t01 * (q.x - p.x), p.y + t01 * (q.y - p.y)));
            }
        }
        segments.push_back({down, up});
    }
}

// Phase 2: chain segments into closed loops through their shared edges.
static Status chain_loops(const std::vector<Segment>& segments, const std::unordered_map<uint64_t, Vec2>& points,
                          size_t plane, double h, std::vector<std::vector<Vec2>>& loops) {
    std::unordered_map<uint64_t, uint32_t> starting;
    starting.reserve(segments.size() * 2);
    for (size_t s = 0; s < segments.size(); ++s)
        if (!starting.emplace(segments[s].from, uint32_t(s)).second)
            return input_error("slice: plane " + std::to_string(plane) + " (height " + std::to_string(h) +
                               "): mesh is not manifold there (an edge crossed by more than two triangles)");
    std::vector<uint8_t> used(segments.size(), 0);
    for (size_t s0 = 0; s0 < segments.size(); ++s0) {
        if (used[s0]) continue;
        std::vector<Vec2> loop;
        size_t s = s0;
        for (;;) {
            used[s] = 1;
            loop.push_back(points.at(segments[s].from));
            auto it = starting.find(segments[s].to);
            if (it == starting.end())
                return input_error("slice: plane " + std::to_string(plane) + " (height " + std::to_string(h) +
                                   "): mesh is open there (a contour does not close)");
            s = it->second;
            if (s == s0) break;
            if (used[s])
                return input_error("slice: plane " + std::to_string(plane) + " (height " + std::to_string(h) +
                                   "): mesh is not manifold there (contours merge)");
        }
        loops.push_back(std::move(loop));
    }
    return ok_status();
}

// Phase 3: drop repeated points (vertices on the plane) and degenerate loops.
static bool clean_loop(std::vector<Vec2>& loop, double tolerance) {
    std::vector<Vec2> out;
    out.reserve(loop.size());
    for (const Vec2& p : loop)
        if (out.empty() || glm::length(p - out.back()) > tolerance) out.push_back(p);
    while (out.size() > 1 && glm::length(out.front() - out.back()) <= tolerance) out.pop_back();
    loop = std::move(out);
    if (loop.size() < 3) return false;
    return std::abs(signed_area2(loop.data(), loop.size())) > tolerance * tolerance;
}

}  // namespace

// The extents along `axis` of the triangles taking part in a self-intersection,
// sorted and merged where they overlap.
static std::vector<std::pair<double, double>> self_intersection_spans(std::span<const Vec3> positions,
                                                                      std::span<const uint32_t> indices, int axis) {
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    if (count_self_intersections(positions, indices, 0, &pairs) == 0) return {};
    std::vector<std::pair<double, double>> spans;
    for (auto [a, b] : pairs)
        for (uint32_t t : {a, b}) {
            double lo = 1e300, hi = -1e300;
            for (int k = 0; k < 3; ++k) {
                double h = positions[indices[3 * size_t(t) + k]][axis];
                lo = std::min(lo, h);
                hi = std::max(hi, h);
            }
            spans.push_back({lo, hi});
        }
    std::sort(spans.begin(), spans.end());
    std::vector<std::pair<double, double>> merged;
    for (auto span : spans)
        if (!merged.empty() && span.first <= merged.back().second)
            merged.back().second = std::max(merged.back().second, span.second);
        else
            merged.push_back(span);
    return merged;
}

size_t drop_planes_through_self_intersections(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                              int axis, std::vector<double>& planes) {
    const auto spans = self_intersection_spans(positions, indices, axis);
    const size_t before = planes.size();
    std::erase_if(planes, [&](double h) {
        for (auto [lo, hi] : spans)
            if (h >= lo && h <= hi) return true;
        return false;
    });
    return before - planes.size();
}

PlaneMoves move_planes_off_self_intersections(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                                              int axis, std::vector<double>& planes) {
    PlaneMoves out;
    const auto spans = self_intersection_spans(positions, indices, axis);
    if (spans.empty()) return out;
    std::sort(planes.begin(), planes.end());
    const std::vector<double> given = planes;
    std::vector<double> kept;
    for (size_t k = 0; k < given.size(); ++k) {
        const double h = given[k];
        double gap = 1e300;  // to the nearer neighbour; a lone plane may move by its slab's tenth
        if (k > 0) gap = std::min(gap, h - given[k - 1]);
        if (k + 1 < given.size()) gap = std::min(gap, given[k + 1] - h);
        auto blocked = std::find_if(spans.begin(), spans.end(), [&](auto s) { return h >= s.first && h <= s.second; });
        if (blocked == spans.end()) {
            kept.push_back(h);
            continue;
        }
        if (gap == 1e300) gap = 10 * (blocked->second - blocked->first) + 1e-300;
        // Just past either end of the merged span, whichever is nearer; the
        // margin keeps the plane off the span's end vertices.
        const double margin = kPlaneMoveMargin * gap;
        const double below = blocked->first - margin, above = blocked->second + margin;
        const bool below_free = blocked == spans.begin() || std::prev(blocked)->second < below;
        const bool above_free = std::next(blocked) == spans.end() || std::next(blocked)->first > above;
        double best = 1e300;
        if (below_free && h - below <= kPlaneMoveLimit * gap) best = below;
        if (above_free && above - h <= kPlaneMoveLimit * gap && above - h < std::abs(h - best)) best = above;
        if (best == 1e300) {
            ++out.dropped;
            continue;
        }
        ++out.moved;
        out.largest_move = std::max(out.largest_move, std::abs(best - h) / gap);
        kept.push_back(best);
    }
    planes = std::move(kept);
    return out;
}

std::vector<double> evenly_spaced_planes(double lo, double hi, size_t count) {
    std::vector<double> out(count);
    for (size_t k = 0; k < count; ++k) out[k] = lo + (double(k) + 0.5) * (hi - lo) / double(count);
    return out;
}

Result<ContourStack> slice_mesh(std::span<const Vec3> positions, std::span<const uint32_t> indices, int axis,
                                std::span<const double> planes, const std::string& structure) {
    if (axis < 0 || axis > 2) return input_error("slice: axis must be 0, 1 or 2");
    if (indices.size() % 3 != 0) return input_error("slice: index count is not a multiple of 3");
    for (size_t k = 0; k < indices.size(); ++k)
        if (indices[k] >= positions.size())
            return input_error("slice: index " + std::to_string(k) + " is out of range");
    std::vector<Vec3> pos(positions.size());
    Aabb box;
    for (size_t k = 0; k < positions.size(); ++k) {
        pos[k] = permuted(positions[k], axis);
        box.extend(pos[k]);
    }
    // Points closer than this to the previous one merge: a mesh vertex a hair
    // off the plane otherwise leaves a micro-zigzag that no band can follow
    // without folding.
    const double tolerance = kMergeDistance * std::max(box.extent(), 1e-300);

    std::vector<double> heights(planes.begin(), planes.end());
    std::sort(heights.begin(), heights.end());
    ContourStack stack;
    if (!structure.empty()) stack.structures.push_back({structure, structure, Vec3(0.8, 0.8, 0.8)});
    std::vector<Segment> segments;
    std::unordered_map<uint64_t, Vec2> points;
    for (size_t p = 0; p < heights.size(); ++p) {
        const double h = heights[p];
        if (!std::isfinite(h)) return input_error("slice: plane " + std::to_string(p) + " is not finite");
        collect_segments(pos, indices, h, segments, points);
        std::vector<std::vector<Vec2>> loops;
        if (auto s = chain_loops(segments, points, p, h, loops); !s) return s.error();
        Slice slice;
        slice.z = h;
        slice.source_index = stack.slices.size();
        for (auto& loop : loops) {
            if (!clean_loop(loop, tolerance)) continue;
            Contour c;
            c.points = std::move(loop);
            c.structure = structure;
            c.source_slice = slice.source_index;
            c.source_contour = slice.contours.size();
            slice.contours.push_back(std::move(c));
        }
        if (slice.contours.empty()) continue;
        if (!stack.slices.empty() && h - stack.slices.back().z < kSliceMergeTolerance) {
            for (auto& c : slice.contours) stack.slices.back().contours.push_back(std::move(c));
            continue;
        }
        stack.slices.push_back(std::move(slice));
    }
    return stack;
}

}  // namespace body
