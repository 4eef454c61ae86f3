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

// Greedy shortest-diagonal tiling (Christiansen & Sederberg 1978), starting at
// the upper vertex nearest lower[0] after aligning centroids; a fold is avoided
// where the other move does not fold.
void tile_greedy(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles) {
    using tiling_detail::Band;
    const size_t m = lower.size(), n = upper.size();
    Vec3 cl(0.0), cu(0.0);
    for (const Vec3& p : lower) cl += p / double(m);
    for (const Vec3& p : upper) cu += p / double(n);
    size_t j0 = 0;
    double best = 1e300;
    for (size_t j = 0; j < n; ++j) {
        Vec3 d = (upper[j] - cu) - (lower[0] - cl);
        double d2 = d.x * d.x + d.y * d.y;
        if (d2 < best) best = d2, j0 = j;
    }
    Band band(lower, upper);
    std::vector<uint8_t> moves;
    moves.reserve(m + n);
    size_t a = 0, b = 0;
    while (a < m || b < n) {
        size_t i = a % m, j = (j0 + b) % n;
        bool up;
        if (a == m)
            up = true;
        else if (b == n)
            up = false;
        else {
            auto lc = band.lower_cost(i, j), uc = band.upper_cost(i, j);
            if (lc.folds != uc.folds)
                up = uc.folds < lc.folds;
            else {
                Vec3 dl = lower[(i + 1) % m] - upper[j], du = upper[(j + 1) % n] - lower[i];
                up = glm::dot(du, du) < glm::dot(dl, dl);
            }
        }
        moves.push_back(up ? 1 : 0);
        (up ? b : a)++;
    }
    tiling_detail::emit_path(m, n, 0, j0, moves, triangles);
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
