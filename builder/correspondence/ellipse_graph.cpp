// The thesis correspondence: each contour is summarised by its best-fit ellipse
// 5-tuple (xc, yc, theta, a, b); the weight between contours A and B is
//   W = x*D + y*O,  D = |tuple(A) - tuple(B)|,  O = 2 / (Overlap(A,B) + Overlap(B,A)),
//   x = (Overlap(A, Ellipse(A)) + Overlap(B, Ellipse(B))) / 2,  y = 1 - x,
// where Overlap(P, Q) is the fraction of P's area covered by Q. A minimum
// spanning path visits every contour of the plane with fewer contours: each
// of them is linked to its cheapest partner, and each contour of the other
// plane to its cheapest partner among them (that is where branches come from).
// Pairs whose weight exceeds a cut-off are not linked (the contour ends).
//
// References:
//   BodyGen/BodyView thesis, section 2.4.2 (the weight above).
//   M. M. Skinner, "Contour correspondence by minimum spanning path", 1991;
//   Y. Bresler, J. A. Fessler, A. Macovski, "A Bayesian approach to
//     reconstruction from incomplete projections of a multiple object 3D
//     domain", IEEE PAMI 11(8), 1989 (generalised ellipses).
//   The 5-tuple is made unit-free here: lengths are divided by the pair's mean
//   size sqrt(area) and the angle is weighted by the ellipse's anisotropy.
#include <algorithm>
#include <cmath>
#include <limits>

#include "builder/correspondence/correspondence.h"

namespace body {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxWeight = 1.0;  // above this, two contours are not the same piece
constexpr double kNoOverlapO = 1e3;

std::vector<Vec2> ellipse_polygon(const Ellipse5& e, int segments) {
    std::vector<Vec2> out(static_cast<size_t>(segments));
    const double c = std::cos(e.theta), s = std::sin(e.theta);
    for (int i = 0; i < segments; ++i) {
        const double t = 2 * kPi * i / segments;
        const double u = e.a * std::cos(t), v = e.b * std::sin(t);
        out[size_t(i)] = {e.xc + c * u - s * v, e.yc + s * u + c * v};
    }
    return out;
}

struct Summary {
    Ellipse5 e;
    double area = 0;
    double fit = 0;  // Overlap(A, Ellipse(A))
};

Summary summarise(PolygonSpan p) {
    Summary s;
    s.e = fit_ellipse(p);
    s.area = std::abs(signed_area2(p.data(), p.size())) / 2;
    if (s.e.b > 0 && s.area > 0) {
        auto poly = ellipse_polygon(s.e, 64);
        s.fit = std::clamp(polygon_overlap_area(p, poly) / s.area, 0.0, 1.0);
    }
    return s;
}

double weight(const Summary& A, PolygonSpan a, const Summary& B, PolygonSpan b) {
    const double size = std::sqrt((A.area + B.area) / 2);
    if (!(size > 0)) return std::numeric_limits<double>::infinity();
    double dtheta = std::abs(A.e.theta - B.e.theta);
    dtheta = std::min(dtheta, kPi - dtheta);
    const double aniso = 0.5 * ((A.e.a - A.e.b) / (A.e.a + A.e.b) + (B.e.a - B.e.b) / (B.e.a + B.e.b));
    const double dx = (A.e.xc - B.e.xc) / size, dy = (A.e.yc - B.e.yc) / size;
    const double da = (A.e.a - B.e.a) / size, db = (A.e.b - B.e.b) / size, dt = dtheta * aniso;
    const double D = std::sqrt(dx * dx + dy * dy + da * da + db * db + dt * dt);
    const double overlap = polygon_overlap_area(a, b);
    const double sum = overlap / A.area + overlap / B.area;
    const double O = sum > 0 ? std::min(kNoOverlapO, 2 / sum) : kNoOverlapO;
    const double x = (A.fit + B.fit) / 2, y = 1 - x;
    // O is 1 for identical regions; shift it so that identical contours weigh 0 either way.
    return x * D + y * (O - 1);
}

}  // namespace

Ellipse5 fit_ellipse(PolygonSpan p) {
    double A = 0, cx = 0, cy = 0, ixx = 0, iyy = 0, ixy = 0;
    const size_t n = p.size();
    // Moments about the first vertex keep the sums well conditioned.
    const Vec2 o = n ? p[0] : Vec2(0);
    for (size_t i = 0; i < n; ++i) {
        const Vec2 a = p[i] - o, b = p[(i + 1) % n] - o;
        const double c = a.x * b.y - b.x * a.y;
        A += c;
        cx += (a.x + b.x) * c;
        cy += (a.y + b.y) * c;
        ixx += (a.x * a.x + a.x * b.x + b.x * b.x) * c;
        iyy += (a.y * a.y + a.y * b.y + b.y * b.y) * c;
        ixy += (a.x * b.y + 2 * a.x * a.y + 2 * b.x * b.y + b.x * a.y) * c;
    }
    Ellipse5 e;
    if (A == 0) return e;
    A *= 0.5;
    cx /= 6 * A;
    cy /= 6 * A;
    const double mxx = ixx / (12 * A) - cx * cx, myy = iyy / (12 * A) - cy * cy, mxy = ixy / (24 * A) - cx * cy;
    const double tr = mxx + myy, det = mxx * myy - mxy * mxy;
    const double disc = std::sqrt(std::max(0.0, tr * tr / 4 - det));
    const double l1 = tr / 2 + disc, l2 = std::max(0.0, tr / 2 - disc);
    e.xc = cx + o.x;
    e.yc = cy + o.y;
    e.theta = 0.5 * std::atan2(2 * mxy, mxx - myy);
    if (e.theta < 0) e.theta += kPi;
    e.a = 2 * std::sqrt(l1);
    e.b = 2 * std::sqrt(l2);
    return e;
}

std::vector<ContourLink> correspond_by_ellipse(std::span<const PolygonSpan> lower, std::span<const PolygonSpan> upper) {
    std::vector<ContourLink> links;
    if (lower.empty() || upper.empty()) return links;
    std::vector<Summary> sl, su;
    for (auto p : lower) sl.push_back(summarise(p));
    for (auto p : upper) su.push_back(summarise(p));
    std::vector<double> w(lower.size() * upper.size());
    for (size_t i = 0; i < lower.size(); ++i)
        for (size_t j = 0; j < upper.size(); ++j) w[i * upper.size() + j] = weight(sl[i], lower[i], su[j], upper[j]);
    // Every contour takes its cheapest partner on the other plane; the plane with
    // fewer contours is always fully visited, the other plane's choices make branches.
    for (uint32_t i = 0; i < lower.size(); ++i) {
        uint32_t best = 0;
        for (uint32_t j = 1; j < upper.size(); ++j)
            if (w[i * upper.size() + j] < w[i * upper.size() + best]) best = j;
        if (w[i * upper.size() + best] <= kMaxWeight) links.push_back({i, best});
    }
    for (uint32_t j = 0; j < upper.size(); ++j) {
        uint32_t best = 0;
        for (uint32_t i = 1; i < lower.size(); ++i)
            if (w[i * upper.size() + j] < w[best * upper.size() + j]) best = i;
        if (w[best * upper.size() + j] <= kMaxWeight) links.push_back({best, j});
    }
    return links;
}

}  // namespace body
