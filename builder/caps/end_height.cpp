// End height: area-rate extrapolation of an ending loop (end_height.h).
#include "builder/caps/end_height.h"

#include <algorithm>

namespace body {

namespace {

// For every vertex v, sums value(w, side) over its edge neighbours w on a lower
// and on a higher slice; `value` returns false where w has nothing to give.
// Each triangle edge is seen from both of its triangles: every neighbour
// counts twice, which a mean does not see.
template <class Value>
void sum_over_neighbours(std::span<const Vec3> positions, std::span<const uint32_t> triangles, Value&& value,
                         std::vector<Vec3>& below, std::vector<uint32_t>& below_n, std::vector<Vec3>& above,
                         std::vector<uint32_t>& above_n) {
    const size_t n = positions.size();
    below.assign(n, Vec3(0.0));
    above.assign(n, Vec3(0.0));
    below_n.assign(n, 0);
    above_n.assign(n, 0);
    for (size_t t = 0; t + 2 < triangles.size(); t += 3)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = triangles[t + e], b = triangles[t + (e + 1) % 3];
            for (const auto& [v, w] : {std::pair{a, b}, std::pair{b, a}}) {
                const bool is_below = positions[w].z < positions[v].z;
                if (!is_below && !(positions[w].z > positions[v].z)) continue;
                Vec3 given;
                if (!value(w, is_below, given)) continue;
                (is_below ? below : above)[v] += given;
                ++(is_below ? below_n : above_n)[v];
            }
        }
}

}  // namespace

void rung_partners(std::span<const Vec3> positions, std::span<const uint32_t> triangles, RungPartners& out) {
    sum_over_neighbours(
        positions, triangles,
        [&](uint32_t w, bool, Vec3& given) {
            given = positions[w];
            return true;
        },
        out.below, out.below_n, out.above, out.above_n);
    // The second level: the means of the partners' own means, one slice further.
    sum_over_neighbours(
        positions, triangles,
        [&](uint32_t w, bool below, Vec3& given) {
            const uint32_t count = below ? out.below_n[w] : out.above_n[w];
            if (count == 0) return false;
            given = (below ? out.below[w] : out.above[w]) / double(count);
            return true;
        },
        out.below2, out.below2_n, out.above2, out.above2_n);
}

namespace {

// The mean of v's partners on one side; false when it has none.
bool mean_partner(const RungPartners& partners, bool below, int level, uint32_t v, Vec3& out) {
    const auto& counts =
        level == 1 ? (below ? partners.below_n : partners.above_n) : (below ? partners.below2_n : partners.above2_n);
    if (v >= counts.size() || counts[v] == 0) return false;
    const auto& sums =
        level == 1 ? (below ? partners.below : partners.above) : (below ? partners.below2 : partners.above2);
    out = sums[v] / double(counts[v]);
    return true;
}

double signed_area(const std::vector<Vec2>& p) {
    double a = 0;
    for (size_t i = 0; i < p.size(); ++i) a += p[i].x * p[(i + 1) % p.size()].y - p[(i + 1) % p.size()].x * p[i].y;
    return 0.5 * a;
}

// Smallest h > 0 with a0 + b h + c h^2 = 0, or where it comes closest to 0
// while falling (a double root seen through rounding); -1 when neither.
double first_zero(double a0, double b, double c) {
    if (std::abs(c) < 1e-12 * (std::abs(b) + std::abs(a0))) return b < 0 ? -a0 / b : -1;
    const double d = b * b - 4 * c * a0;
    if (d < 0) return c > 0 && b < 0 ? -b / (2 * c) : -1;
    const double r = std::sqrt(d), h1 = (-b - r) / (2 * c), h2 = (-b + r) / (2 * c);
    const double lo = std::min(h1, h2), hi = std::max(h1, h2);
    return lo > 0 ? lo : hi > 0 ? hi : -1;
}

}  // namespace

EndHeight end_height(std::span<const Vec2> xy, std::span<const uint32_t> ids, std::span<const Vec3> positions,
                     const RungPartners& partners, bool up, double limit) {
    // The loop and its partners one and two slices back, with their mean
    // distances back from the loop's slice.
    const size_t n = xy.size();
    std::vector<Vec2> ring0(xy.begin(), xy.end()), ring1(n), ring2(n);
    double d1 = 0, d2 = 0;
    size_t n1 = 0, n2 = 0;
    for (size_t i = 0; i < n; ++i) {
        const double z = positions[ids[i]].z;
        Vec3 w1(xy[i], z), w2;
        if (mean_partner(partners, up, 1, ids[i], w1)) d1 += std::abs(z - w1.z), ++n1;
        w2 = w1;
        if (mean_partner(partners, up, 2, ids[i], w2)) d2 += std::abs(z - w2.z), ++n2;
        ring1[i] = Vec2(w1.x, w1.y);
        ring2[i] = Vec2(w2.x, w2.y);
    }
    EndHeight out;
    out.height = limit;
    if (n1 == 0) return out;
    d1 /= double(n1);
    const double s0 = signed_area(ring0), a0 = std::abs(s0), a1 = std::abs(signed_area(ring1));
    // Linear in the last gap; quadratic through three slices where the ring
    // two slices back is whole and keeps the orientation (a sphere's
    // cross-section is exactly quadratic, a cone's has a double root).
    double b = (a0 - a1) / d1, c = 0;
    const double s2 = signed_area(ring2);
    if (n2 == n && d2 > 1.5 * d1 && s2 * s0 > 0 && signed_area(ring1) * s0 > 0) {
        d2 /= double(n2);
        const double f12 = (a1 - std::abs(s2)) / (d2 - d1);
        c = (b - f12) / d2;
        b += c * d1;
    }
    const double h = first_zero(a0, b, c);
    if (h > 0 && h < limit) out.height = std::max(h, 0.1 * limit), out.closing = true;
    return out;
}

}  // namespace body
