// Branching by nearest-branch partition of the single contour.
//
// References:
//   H. N. Christiansen, T. W. Sederberg, "Conversion of complex contour line
//     definitions into polygonal element mosaics", SIGGRAPH 1978 (composite
//     contours at branches).
//   D. Meyers, S. Skinner, K. Sloan, "Surfaces from contours", ACM TOG 11(3),
//     1992 (splitting the pre-branch contour along the branches' bisector,
//     here approximated by the nearest-branch partition and straight chords).
//   BodyGen/BodyView thesis, section 2.6 (the overlapping method it replaces).
#include <algorithm>
#include <cmath>

#include "builder/branching/branching.h"

namespace body {
namespace {

struct Run {
    size_t start = 0, length = 0;
    uint32_t owner = 0;
};

double distance_to_polygon(const Vec2& p, std::span<const Vec2> poly) {
    double best = 1e300;
    for (size_t i = 0; i < poly.size(); ++i) {
        const Vec2 a = poly[i], ab = poly[(i + 1) % poly.size()] - a;
        const double l2 = glm::dot(ab, ab);
        const double t = l2 > 0 ? std::clamp(glm::dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
        best = std::min(best, glm::length(a + ab * t - p));
    }
    return best;
}

// Phase 1: each vertex goes to its nearest branch.
std::vector<uint32_t> nearest_owner(std::span<const uint32_t> single, std::span<const std::span<const Vec2>> branches,
                                    const std::vector<Vec3>& positions) {
    std::vector<uint32_t> owner(single.size(), 0);
    for (size_t i = 0; i < single.size(); ++i) {
        const Vec2 p(positions[single[i]]);
        double best = 1e300;
        for (uint32_t b = 0; b < branches.size(); ++b) {
            const double d = distance_to_polygon(p, branches[b]);
            if (d < best) best = d, owner[i] = b;
        }
    }
    return owner;
}

std::vector<Run> runs_of(const std::vector<uint32_t>& owner) {
    const size_t n = owner.size();
    size_t start = 0;
    while (start < n && owner[start] == owner[(start + n - 1) % n]) ++start;
    std::vector<Run> runs;
    if (start == n) return {Run{0, n, owner[0]}};
    for (size_t k = 0; k < n;) {
        Run r{(start + k) % n, 0, owner[(start + k) % n]};
        while (k < n && owner[(start + k) % n] == r.owner) ++r.length, ++k;
        runs.push_back(r);
    }
    return runs;
}

// Phase 2: merge runs until every branch owns at most one arc, then give an arc
// to every branch that owns none (splitting the longest arc).
Status settle_runs(std::vector<Run>& runs, uint32_t branch_count) {
    for (;;) {
        std::vector<uint32_t> count(branch_count, 0);
        for (const Run& r : runs) ++count[r.owner];
        size_t victim = SIZE_MAX;
        for (size_t k = 0; k < runs.size(); ++k)
            if (count[runs[k].owner] > 1 && (victim == SIZE_MAX || runs[k].length < runs[victim].length)) victim = k;
        if (victim == SIZE_MAX) break;
        const size_t n = runs.size(), prev = (victim + n - 1) % n, next = (victim + 1) % n;
        runs[victim].owner = runs[runs[prev].length >= runs[next].length ? prev : next].owner;
        // Coalesce neighbours with equal owners.
        std::vector<Run> merged;
        for (const Run& r : runs) {
            if (!merged.empty() && merged.back().owner == r.owner)
                merged.back().length += r.length;
            else
                merged.push_back(r);
        }
        if (merged.size() > 1 && merged.front().owner == merged.back().owner) {
            merged.back().length += merged.front().length;
            merged.erase(merged.begin());
        }
        runs = std::move(merged);
    }
    for (uint32_t b = 0; b < branch_count; ++b) {
        if (std::any_of(runs.begin(), runs.end(), [&](const Run& r) { return r.owner == b; })) continue;
        auto longest =
            std::max_element(runs.begin(), runs.end(), [](const Run& x, const Run& y) { return x.length < y.length; });
        if (longest->length < 2) return input_error("too few vertices to split between the branches");
        Run tail = *longest;
        tail.length = longest->length / 2;
        longest->length -= tail.length;
        tail.start = longest->start + longest->length;
        tail.owner = b;
        runs.insert(longest + 1, tail);
    }
    return ok_status();
}

}  // namespace

const char* branching_method_name(BranchingMethod method) {
    return method == BranchingMethod::Partition ? "partition" : "overlap";
}

Result<std::vector<std::vector<uint32_t>>> partition_contour(std::span<const uint32_t> single,
                                                             std::span<const std::span<const Vec2>> branches,
                                                             double chord_z, std::vector<Vec3>& positions) {
    const size_t n = single.size();
    if (branches.size() < 2) return input_error("partition: needs at least two branches");
    if (n < branches.size() * 2) return input_error("partition: contour has too few vertices for its branches");
    std::vector<Run> runs = runs_of(nearest_owner(single, branches, positions));
    auto settled = settle_runs(runs, uint32_t(branches.size()));
    if (!settled) return settled.error();

    // Phase 3: chords from each split vertex (first vertex of a run) to the centre.
    double perimeter = 0;
    for (size_t i = 0; i < n; ++i) perimeter += glm::length(positions[single[(i + 1) % n]] - positions[single[i]]);
    const double step = perimeter / double(n);
    Vec2 centre(0.0);
    for (const Run& r : runs) centre += Vec2(positions[single[r.start % n]]);
    centre /= double(runs.size());
    const uint32_t centre_id = uint32_t(positions.size());
    positions.emplace_back(centre.x, centre.y, chord_z);
    std::vector<std::vector<uint32_t>> chords(runs.size());  // split vertex -> centre, excluding both ends
    for (size_t r = 0; r < runs.size(); ++r) {
        const Vec2 s(positions[single[runs[r].start % n]]);
        const double length = glm::length(centre - s);
        const int k = std::max(1, int(std::lround(length / std::max(step, 1e-300))));
        for (int t = 1; t < k; ++t) {
            const Vec2 p = s + (centre - s) * (double(t) / k);
            chords[r].push_back(uint32_t(positions.size()));
            positions.emplace_back(p.x, p.y, chord_z);
        }
    }

    // Phase 4: piece r = arc of run r up to the next run's first vertex, then the
    // next chord towards the centre and this run's chord back.
    std::vector<std::vector<uint32_t>> pieces(branches.size());
    for (size_t r = 0; r < runs.size(); ++r) {
        const size_t next = (r + 1) % runs.size();
        std::vector<uint32_t>& piece = pieces[runs[r].owner];
        for (size_t k = 0; k <= runs[r].length; ++k) piece.push_back(single[(runs[r].start + k) % n]);
        piece.insert(piece.end(), chords[next].begin(), chords[next].end());
        piece.push_back(centre_id);
        piece.insert(piece.end(), chords[r].rbegin(), chords[r].rend());
    }
    return pieces;
}

}  // namespace body
