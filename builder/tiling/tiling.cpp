// Tiling dispatch: validates a contour pair and hands it to the chosen method.
// Methods: tiling_optimal.cpp (Fuchs, Kedem & Uselton 1977) and
// tiling_multires.cpp (Meyers, Skinner & Sloan 1992, as in the BodyGen thesis 2.5.2).
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
    return ok_status();
}

}  // namespace body
