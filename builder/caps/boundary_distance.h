#pragma once
// Distance from points to a region's boundary (all its loops), for the dome
// cap's height field, in O(1) per query after O(n + G^2) setup: the boundary
// is sampled (at most 4 samples per point on average), each sample seeds its
// cell of a G x G grid over the region's box (G <= 1024, about sqrt of the
// samples), and a two-pass sweep gives every cell its nearest seed (a vector
// distance transform). A query returns the distance to the edges of the seeds
// of its cell and the 8 around it: approximate where two edges are almost
// equally near, within a few cells otherwise; the dome needs no more.
#include <cstdint>
#include <span>
#include <vector>

#include "shared/geometry.h"

namespace body {

class BoundaryDistance {
public:
    explicit BoundaryDistance(std::span<const std::span<const Vec2>> loops);
    double operator()(const Vec2& p) const;

private:
    struct Sample {
        Vec2 p;
        Vec2 a, b;  // the boundary edge it lies on
    };
    size_t cell_of(const Vec2& p) const;
    Vec2 centre(size_t x, size_t y) const;
    void sweep();
    std::vector<Sample> samples_;
    std::vector<uint32_t> nearest_;  // per cell: a sample, UINT32_MAX before the sweep reaches it
    size_t width_ = 0, height_ = 0;
    Vec2 origin_{0.0};
    double cell_ = 1.0;
};

}  // namespace body
