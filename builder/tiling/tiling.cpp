// Tiling dispatch: validates a contour pair and hands it to the chosen method.
// Methods: tiling_optimal.cpp (Fuchs, Kedem & Uselton 1977) and
// tiling_multires.cpp (Meyers, Skinner & Sloan 1992, as in the BodyGen thesis 2.5.2);
// every band then gets the fold check of tiling_unfold.cpp.
#include "builder/tiling/tiling.h"

#include <cmath>
#include <string>

#include "builder/tiling/tiling_internal.h"

namespace body {

static Status validate_contour(std::span<const Vec3> c, const char* which) {
    if (c.size() < 3)
        return input_error(std::string("tiling: ") + which + " contour has " + std::to_string(c.size()) +
                           " points, needs at least 3");
    if (c.size() >= (size_t(1) << 31)) return input_error(std::string("tiling: ") + which + " contour too large");
    for (size_t k = 0; k < c.size(); ++k)
        if (!std::isfinite(c[k].x) || !std::isfinite(c[k].y) || !std::isfinite(c[k].z))
            return input_error(std::string("tiling: ") + which + " contour point " + std::to_string(k) +
                               " is not finite");
    return ok_status();
}

// Pairs with at most this many vertex pairs whose band still crosses after the
// repair try the area-only optimum (O(m n) bits of memory).
constexpr double kAreaOnlyCells = 4e6;

// Pairs with at most this many vertices in all whose band still crosses after
// the repair try every start of the optimal tiling.
constexpr size_t kEveryStartVertices = 48;

// The methods emit their path in order: the cyclic tiling it takes.
static tiling_detail::CyclicTiling as_path(const tiling_detail::Band& band, const std::vector<uint32_t>& triangles) {
    const uint32_t m = uint32_t(band.lower.size());
    std::vector<uint8_t> moves(triangles.size() / 3);
    for (size_t t = 0; t < moves.size(); ++t) moves[t] = triangles[3 * t + 1] < m ? 0 : 1;
    return tiling_detail::CyclicTiling(band, triangles[0], triangles[2] - m, moves);
}

const char* tiling_method_name(TilingMethod method) {
    switch (method) {
        case TilingMethod::Optimal: return "optimal";
        case TilingMethod::Multires: return "multires";
    }
    return "unknown";
}

Status tile_band(std::span<const Vec3> lower, std::span<const Vec3> upper, TilingMethod method,
                 std::vector<uint32_t>& triangles) {
    if (auto s = validate_contour(lower, "lower"); !s) return s;
    if (auto s = validate_contour(upper, "upper"); !s) return s;
    triangles.clear();
    triangles.reserve(3 * (lower.size() + upper.size()));
    switch (method) {
        case TilingMethod::Optimal: tile_optimal(lower, upper, triangles); break;
        case TilingMethod::Multires: tile_multires(lower, upper, triangles); break;
    }
    // Fold check: a band whose triangles cross is repaired by diagonal flips
    // (tiling_unfold.cpp); where crossings are left, the minimum-area tiling
    // without the corner charge (pairs up to kAreaOnlyCells), then on tiny
    // pairs the optimal path from every start, are repaired too and the band
    // with fewer crossings (then lower cost) is kept.
    tiling_detail::Band band(lower, upper);
    tiling_detail::CyclicTiling path = as_path(band, triangles);
    size_t left = tiling_detail::unfold(path);
    if (left > 0 && double(lower.size()) * double(upper.size()) <= kAreaOnlyCells) {
        std::vector<uint32_t> area_only;
        tile_optimal(lower, upper, area_only, false);
        tiling_detail::CyclicTiling other = as_path(band, area_only);
        const size_t other_left = tiling_detail::unfold(other);
        if (other_left < left || (other_left == left && other.total() < path.total())) {
            path = std::move(other);
            left = other_left;
        }
    }
    // Small bands still crossing: the optimal path through each spanning edge
    // from lower vertex 0, each repaired in turn.
    for (uint32_t j = 0; left > 0 && j < upper.size() && lower.size() + upper.size() <= kEveryStartVertices; ++j) {
        std::vector<uint32_t> through;
        tile_optimal_from(lower, upper, 0, j, through);
        tiling_detail::CyclicTiling other = as_path(band, through);
        const size_t other_left = tiling_detail::unfold(other);
        if (other_left < left || (other_left == left && other.total() < path.total())) {
            path = std::move(other);
            left = other_left;
        }
    }
    triangles.clear();
    path.emit(triangles);
    return ok_status();
}

}  // namespace body
