#pragma once
// Sampled Hausdorff distance between triangle meshes, used to check the error a
// progressive mesh stores (tests) and to compare simplifiers (bench/bench_pm.cpp).
//
// Samples on a mesh: every vertex, every edge midpoint, and four interior points
// per triangle (centroid and the three points (2/3, 1/6, 1/6)); the distance of a
// sample to the other mesh is exact (closest point on a triangle, uniform grid).
#include <cstdint>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body::lod {

class SurfaceDistance {
public:
    SurfaceDistance(std::span<const Vec3> positions, std::span<const uint32_t> indices);
    // Distance from p to the nearest point of the surface (infinity if it has no triangles).
    double distance(const Vec3& p) const;

private:
    std::vector<Vec3> pos_;
    std::vector<uint32_t> idx_;
    Vec3 origin_{0.0};
    double cell_ = 1.0;
    int dims_[3] = {1, 1, 1};
    std::vector<uint32_t> cell_begin_, cell_items_;
    mutable std::vector<uint32_t> seen_;
    mutable uint32_t query_ = 0;
};

// max over samples of `from` of the distance to `to`.
double one_sided_hausdorff(std::span<const Vec3> from_pos, std::span<const uint32_t> from_idx,
                           const SurfaceDistance& to);

// max of both one-sided distances.
double symmetric_hausdorff(std::span<const Vec3> a_pos, std::span<const uint32_t> a_idx, std::span<const Vec3> b_pos,
                           std::span<const uint32_t> b_idx);

}  // namespace body::lod
