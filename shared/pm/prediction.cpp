// See prediction.h.
#include "shared/pm/prediction.h"

#include <algorithm>
#include <bit>
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
    // One pass over the ring, coordinates relative to v (|d| < 2^16): its extent,
    // its sum and its distances from the plane (n . (p - v) = n . p - n . v, so
    // the same values as from absolute coordinates); a zero plane when there is none.
    const int32_t v0 = v[0], v1 = v[1], v2 = v[2];
    const int64_t n0 = plane ? plane[0] : 0, n1 = plane ? plane[1] : 0, n2 = plane ? plane[2] : 0;
    int32_t d[64][3];
    int32_t lo0 = 65535, lo1 = 65535, lo2 = 65535, hi0 = -65535, hi1 = -65535, hi2 = -65535;
    int32_t all0 = 0, all1 = 0, all2 = 0;
    int64_t hmin = 0, hmax = 0;  // max(hmax, -hmin, 0) is the ring's largest distance
    for (uint32_t t = 0; t < k; ++t) {
        const uint16_t* r = q + size_t(ring[t]) * 3;
        const int32_t x = int32_t(r[0]) - v0, y = int32_t(r[1]) - v1, z = int32_t(r[2]) - v2;
        d[t][0] = x;
        d[t][1] = y;
        d[t][2] = z;
        lo0 = std::min(lo0, x);
        lo1 = std::min(lo1, y);
        lo2 = std::min(lo2, z);
        hi0 = std::max(hi0, x);
        hi1 = std::max(hi1, y);
        hi2 = std::max(hi2, z);
        all0 += x;
        all1 += y;
        all2 += z;
        const int64_t h = n0 * x + n1 * y + n2 * z;
        hmin = std::min(hmin, h);
        hmax = std::max(hmax, h);
    }
    // The child's ring ring[start .. start + length]: its sum, and the Newell sum of
    // its edges (predict_normal closes them into the child's loop; a closed loop's
    // sum does not depend on the origin, the open chain's is taken about v).
    const uint32_t end = start + length < k ? start + length : start + length - k;
    int32_t px = d[start][0], py = d[start][1], pz = d[start][2];
    int32_t child[3] = {px, py, pz};  // relative to v
    int64_t area0 = 0, area1 = 0, area2 = 0;
    for (uint32_t t = 0, i = start + 1 == k ? 0 : start + 1; t < length; ++t, i = i + 1 == k ? 0 : i + 1) {
        const int32_t x = d[i][0], y = d[i][1], z = d[i][2];
        child[0] += x;
        child[1] += y;
        child[2] += z;
        area0 += int64_t(py - y) * (pz + z);
        area1 += int64_t(pz - z) * (px + x);
        area2 += int64_t(px - x) * (py + y);
        px = x;
        py = y;
        pz = z;
    }
    out.child_area[0] = area0;
    out.child_area[1] = area1;
    out.child_area[2] = area2;
    const uint32_t nc = length + 1, np = k - length + 1;
    const int32_t lo[3] = {lo0, lo1, lo2}, hi[3] = {hi0, hi1, hi2}, all[3] = {all0, all1, all2};
    int32_t child_centroid[3], parent_centroid[3];  // relative to v
    for (int a = 0; a < 3; ++a) {
        out.left[a] = d[start][a];
        out.right[a] = d[end][a];
        const int width = std::bit_width(uint32_t(hi[a] - lo[a]));
        out.shift[a] = width > 5 ? uint32_t(width - 5) : 0;
        // Sums of absolute coordinates, as the centroid's definition has them.
        const uint32_t cs = uint32_t(child[a] + int32_t(nc) * v[a]);
        const uint32_t ps = uint32_t(all[a] + int32_t(np) * v[a] - child[a] + d[start][a] + d[end][a]);
        const uint32_t cc = divide_small(cs + nc / 2, nc), pc = divide_small(ps + np / 2, np);
        child_centroid[a] = int32_t(cc) - v[a];
        parent_centroid[a] = int32_t(pc) - v[a];
        out.child[a] = midpoint16(v[a], cc);
        out.parent_centroid[a] = uint16_t(pc);
    }
    const int64_t m0 = n0 < 0 ? -n0 : n0, m1 = n1 < 0 ? -n1 : n1, m2 = n2 < 0 ? -n2 : n2;
    const int64_t top = std::max({m0, m1, m2});
    if (top == 0) {
        out.axis = 3;
        out.axis_shift = 0;
        out.child_dot = out.parent_dot = 0;
        return;
    }
    const int64_t far = std::max(hmax, -hmin);
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
