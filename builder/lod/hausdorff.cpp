// Sampled Hausdorff distance. Closest point on a triangle after C. Ericson,
// "Real-Time Collision Detection" (2005), section 5.1.5.
#include "builder/lod/hausdorff.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "shared/mesh.h"

namespace body::lod {
namespace {

Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const Vec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const Vec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

SurfaceDistance::SurfaceDistance(std::span<const Vec3> positions, std::span<const uint32_t> indices)
    : pos_(positions.begin(), positions.end()), idx_(indices.begin(), indices.end()) {
    const size_t faces = idx_.size() / 3;
    Aabb box = mesh_bounds(pos_);
    if (faces == 0 || box.empty()) return;
    const Vec3 size = box.size();
    const double volume = std::max(size.x, 1e-12) * std::max(size.y, 1e-12) * std::max(size.z, 1e-12);
    cell_ = std::max(std::cbrt(volume / double(faces)) * 1.5, box.extent() * 1e-6);
    origin_ = box.min;
    for (int k = 0; k < 3; ++k) dims_[k] = std::clamp(int(size[k] / cell_) + 1, 1, 1024);
    auto cell_of = [&](const Vec3& p, int k) { return std::clamp(int((p[k] - origin_[k]) / cell_), 0, dims_[k] - 1); };
    const size_t cells = size_t(dims_[0]) * dims_[1] * dims_[2];
    std::vector<uint32_t> count(cells + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
        for (size_t f = 0; f < faces; ++f) {
            Aabb tb;
            for (int k = 0; k < 3; ++k) tb.extend(pos_[idx_[f * 3 + k]]);
            int lo[3], hi[3];
            for (int k = 0; k < 3; ++k) {
                lo[k] = cell_of(tb.min, k);
                hi[k] = cell_of(tb.max, k);
            }
            for (int z = lo[2]; z <= hi[2]; ++z)
                for (int y = lo[1]; y <= hi[1]; ++y)
                    for (int x = lo[0]; x <= hi[0]; ++x) {
                        const size_t c = (size_t(z) * dims_[1] + y) * dims_[0] + x;
                        if (pass == 0)
                            ++count[c + 1];
                        else
                            cell_items_[cell_begin_[c] + count[c]++] = uint32_t(f);
                    }
        }
        if (pass == 0) {
            cell_begin_.assign(cells + 1, 0);
            for (size_t c = 0; c < cells; ++c) cell_begin_[c + 1] = cell_begin_[c] + count[c + 1];
            cell_items_.resize(cell_begin_[cells]);
            std::fill(count.begin(), count.end(), 0);
        }
    }
    seen_.assign(faces, 0);
}

double SurfaceDistance::distance(const Vec3& p) const {
    if (cell_begin_.empty()) return std::numeric_limits<double>::infinity();
    if (++query_ == 0) {
        std::fill(seen_.begin(), seen_.end(), 0);
        query_ = 1;
    }
    int c0[3];
    for (int k = 0; k < 3; ++k) c0[k] = std::clamp(int(std::floor((p[k] - origin_[k]) / cell_)), 0, dims_[k] - 1);
    // Distance from p to the grid box (p may lie outside it).
    double outside = 0.0;
    for (int k = 0; k < 3; ++k) {
        const double lo = origin_[k], hi = origin_[k] + dims_[k] * cell_;
        const double d = p[k] < lo ? lo - p[k] : (p[k] > hi ? p[k] - hi : 0.0);
        outside += d * d;
    }
    outside = std::sqrt(outside);
    double best2 = std::numeric_limits<double>::infinity();
    const int max_r = std::max({dims_[0], dims_[1], dims_[2]});
    for (int r = 0; r <= max_r; ++r) {
        for (int z = c0[2] - r; z <= c0[2] + r; ++z) {
            if (z < 0 || z >= dims_[2]) continue;
            for (int y = c0[1] - r; y <= c0[1] + r; ++y) {
                if (y < 0 || y >= dims_[1]) continue;
                for (int x = c0[0] - r; x <= c0[0] + r; ++x) {
                    if (x < 0 || x >= dims_[0]) continue;
                    if (std::max({std::abs(x - c0[0]), std::abs(y - c0[1]), std::abs(z - c0[2])}) != r) continue;
                    const size_t c = (size_t(z) * dims_[1] + y) * dims_[0] + x;
                    for (uint32_t i = cell_begin_[c]; i < cell_begin_[c + 1]; ++i) {
                        const uint32_t f = cell_items_[i];
                        if (seen_[f] == query_) continue;
                        seen_[f] = query_;
                        const Vec3 q =
                            closest_on_triangle(p, pos_[idx_[f * 3]], pos_[idx_[f * 3 + 1]], pos_[idx_[f * 3 + 2]]);
                        best2 = std::min(best2, glm::dot(q - p, q - p));
                    }
                }
            }
        }
        // Cells beyond ring r are at least r * cell_ (+ the outside gap) away.
        const double reach = outside + r * cell_;
        if (best2 <= reach * reach) break;
    }
    return std::sqrt(best2);
}

double one_sided_hausdorff(std::span<const Vec3> from_pos, std::span<const uint32_t> from_idx,
                           const SurfaceDistance& to) {
    double worst = 0.0;
    std::vector<uint8_t> used(from_pos.size(), 0);
    for (uint32_t v : from_idx) used[v] = 1;
    for (size_t v = 0; v < from_pos.size(); ++v)
        if (used[v]) worst = std::max(worst, to.distance(from_pos[v]));
    for (size_t f = 0; f + 2 < from_idx.size(); f += 3) {
        const Vec3 &a = from_pos[from_idx[f]], &b = from_pos[from_idx[f + 1]], &c = from_pos[from_idx[f + 2]];
        const Vec3 samples[] = {(a + b) * 0.5,
                                (b + c) * 0.5,
                                (c + a) * 0.5,
                                (a + b + c) / 3.0,
                                a * (2.0 / 3) + (b + c) * (1.0 / 6),
                                b * (2.0 / 3) + (a + c) * (1.0 / 6),
                                c * (2.0 / 3) + (a + b) * (1.0 / 6)};
        for (const Vec3& s : samples) worst = std::max(worst, to.distance(s));
    }
    return worst;
}

double symmetric_hausdorff(std::span<const Vec3> a_pos, std::span<const uint32_t> a_idx, std::span<const Vec3> b_pos,
                           std::span<const uint32_t> b_idx) {
    SurfaceDistance da(a_pos, a_idx), db(b_pos, b_idx);
    return std::max(one_sided_hausdorff(a_pos, a_idx, db), one_sided_hausdorff(b_pos, b_idx, da));
}

}  // namespace body::lod
