// See prediction.h.
#include "shared/pm/prediction.h"

#include <algorithm>
#include <bit>
#include <climits>
#include <cmath>

namespace body::pm {

void normal_axis_weights(const float lo[3], const float hi[3], int32_t out[3]) {
    double e[3], w[3];
    for (int k = 0; k < 3; ++k) e[k] = std::max(double(hi[k]) - double(lo[k]), 0.0);
    for (int k = 0; k < 3; ++k) w[k] = e[(k + 1) % 3] * e[(k + 2) % 3];
    const double top = std::max({w[0], w[1], w[2]});
    for (int k = 0; k < 3; ++k) {
        const double r = top > 0.0 ? std::nearbyint(w[k] / top * 256.0) : 1.0;
        out[k] = std::max(1, int32_t(r));
    }
}

void plane_axis_weights(const float lo[3], const float hi[3], int32_t out[3]) {
    double e[3];
    for (int k = 0; k < 3; ++k) e[k] = std::max(double(hi[k]) - double(lo[k]), 0.0);
    const double top = std::max({e[0], e[1], e[2]});
    for (int k = 0; k < 3; ++k) {
        const double r = top > 0.0 ? std::nearbyint(e[k] / top * 256.0) : 1.0;
        out[k] = std::max(1, int32_t(r));
    }
}

void predict_fan(const uint16_t* q, const uint32_t* ring, uint32_t k, uint32_t start, uint32_t length,
                 const uint16_t v[3], const int64_t* plane, FanPrediction& out) {
    // Absolute coordinates in the loops (v subtracted from the results): few running
    // values per loop, so none of them spills.
    uint32_t p[64][3];
    uint32_t lo[3] = {65535, 65535, 65535}, hi[3] = {0, 0, 0}, all[3] = {0, 0, 0};
    for (uint32_t t = 0; t < k; ++t) {
        const uint16_t* r = q + size_t(ring[t]) * 3;
        const uint32_t x = r[0], y = r[1], z = r[2];
        p[t][0] = x;
        p[t][1] = y;
        p[t][2] = z;
        lo[0] = std::min(lo[0], x);
        lo[1] = std::min(lo[1], y);
        lo[2] = std::min(lo[2], z);
        hi[0] = std::max(hi[0], x);
        hi[1] = std::max(hi[1], y);
        hi[2] = std::max(hi[2], z);
        all[0] += x;
        all[1] += y;
        all[2] += z;
    }
    // The child's ring ring[start .. start + length]: its sum, and the Newell sum of
    // its edges (predict_normal closes them into the child's loop; a closed loop's
    // sum does not depend on the origin, the open chain's is taken about v).
    const uint32_t end = start + length < k ? start + length : start + length - k;
    const int32_t v0 = v[0], v1 = v[1], v2 = v[2];
    int32_t px = int32_t(p[start][0]) - v0, py = int32_t(p[start][1]) - v1, pz = int32_t(p[start][2]) - v2;
    int32_t child[3] = {px, py, pz};  // relative to v
    int64_t area[3] = {0, 0, 0};
    for (uint32_t t = 0, i = start + 1 == k ? 0 : start + 1; t < length; ++t, i = i + 1 == k ? 0 : i + 1) {
        const int32_t x = int32_t(p[i][0]) - v0, y = int32_t(p[i][1]) - v1, z = int32_t(p[i][2]) - v2;
        child[0] += x;
        child[1] += y;
        child[2] += z;
        area[0] += int64_t(py - y) * (pz + z);
        area[1] += int64_t(pz - z) * (px + x);
        area[2] += int64_t(px - x) * (py + y);
        px = x;
        py = y;
        pz = z;
    }
    const uint32_t nc = length + 1, np = k - length + 1;
    int32_t child_centroid[3], parent_centroid[3];  // relative to v
    for (int a = 0; a < 3; ++a) {
        out.child_area[a] = area[a];
        out.left[a] = int32_t(p[start][a]) - int32_t(v[a]);
        out.right[a] = int32_t(p[end][a]) - int32_t(v[a]);
        const int width = std::bit_width(hi[a] - lo[a]);
        out.shift[a] = width > 4 ? uint32_t(width - 4) : 0;
        // Sums of absolute coordinates, as the centroid's definition has them.
        const uint32_t cs = uint32_t(child[a] + int32_t(nc) * v[a]);
        const uint32_t ps = all[a] - cs + p[start][a] + p[end][a];
        const uint32_t cc = divide_small(cs + nc / 2, nc), pc = divide_small(ps + np / 2, np);
        child_centroid[a] = int32_t(cc) - v[a];
        parent_centroid[a] = int32_t(pc) - v[a];
        out.child[a] = midpoint16(v[a], cc);
        out.parent_centroid[a] = uint16_t(pc);
    }
    const int64_t n0 = plane ? plane[0] : 0, n1 = plane ? plane[1] : 0, n2 = plane ? plane[2] : 0;
    const int64_t m0 = n0 < 0 ? -n0 : n0, m1 = n1 < 0 ? -n1 : n1, m2 = n2 < 0 ? -n2 : n2;
    const int64_t top = std::max({m0, m1, m2});
    if (top == 0) {
        out.axis = 3;
        out.axis_shift = 0;
        out.child_dot = out.parent_dot = 0;
        return;
    }
    // The ring's largest distance from the plane: max |n . (p - v)| = max(hmax - nv, nv - hmin).
    int64_t hmin = INT64_MAX, hmax = INT64_MIN;
    for (uint32_t t = 0; t < k; ++t) {
        const int64_t h = n0 * p[t][0] + n1 * p[t][1] + n2 * p[t][2];
        hmin = std::min(hmin, h);
        hmax = std::max(hmax, h);
    }
    const int64_t nv = n0 * v0 + n1 * v1 + n2 * v2;
    const int64_t far = std::max({hmax - nv, nv - hmin, int64_t(0)});
    out.normal[0] = n0;
    out.normal[1] = n1;
    out.normal[2] = n2;
    out.axis = m0 >= m1 && m0 >= m2 ? 0 : m1 >= m2 ? 1 : 2;
    const int width = int(std::bit_width(uint64_t(far))) - int(std::bit_width(uint64_t(top))) - 3;
    out.axis_shift = width > 0 ? uint32_t(width) : 0;
    out.child_dot = n0 * child_centroid[0] + n1 * child_centroid[1] + n2 * child_centroid[2];
    out.parent_dot = n0 * parent_centroid[0] + n1 * parent_centroid[1] + n2 * parent_centroid[2];
}

}  // namespace body::pm
