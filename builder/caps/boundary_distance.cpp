// The nearest-seed sweep: P.-E. Danielsson, "Euclidean distance mapping",
// Computer Graphics and Image Processing 14(3), 1980 (vector propagation in
// two raster passes).
#include "builder/caps/boundary_distance.h"

#include <algorithm>
#include <cmath>

namespace body {
namespace {

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double l2 = glm::dot(ab, ab);
    const double s = l2 > 0 ? std::clamp(glm::dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
    return glm::length(a + ab * s - p);
}

}  // namespace

BoundaryDistance::BoundaryDistance(std::span<const std::span<const Vec2>> loops) {
    Vec2 lo(1e300), hi(-1e300);
    double perimeter = 0;
    size_t points = 0;
    for (const auto& loop : loops) {
        for (size_t i = 0; i < loop.size(); ++i) {
            lo = glm::min(lo, loop[i]), hi = glm::max(hi, loop[i]);
            perimeter += glm::length(loop[(i + 1) % loop.size()] - loop[i]);
        }
        points += loop.size();
    }
    if (points == 0) return;
    const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
    const double spacing = std::max(extent / 1024.0, perimeter / double(4 * points));
    for (const auto& loop : loops) {
        for (size_t i = 0; i < loop.size(); ++i) {
            const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()];
            const double len = glm::length(b - a);
            const size_t count = spacing > 0 ? std::max<size_t>(1, size_t(std::ceil(len / spacing))) : 1;
            for (size_t j = 0; j < count; ++j) samples_.push_back({a + (b - a) * (double(j) / double(count)), a, b});
        }
    }
    const size_t g = std::clamp<size_t>(size_t(std::sqrt(double(samples_.size()))), 8, 1024);
    cell_ = extent > 0 ? extent / double(g) : 1.0;
    origin_ = lo;
    width_ = std::min<size_t>(g, size_t((hi.x - lo.x) / cell_) + 1);
    height_ = std::min<size_t>(g, size_t((hi.y - lo.y) / cell_) + 1);
    nearest_.assign(width_ * height_, UINT32_MAX);
    for (uint32_t s = 0; s < samples_.size(); ++s) {
        const size_t c = cell_of(samples_[s].p);
        const Vec2 m = centre(c % width_, c / width_);
        if (nearest_[c] == UINT32_MAX || glm::length(samples_[s].p - m) < glm::length(samples_[nearest_[c]].p - m))
            nearest_[c] = s;
    }
    sweep();
}

size_t BoundaryDistance::cell_of(const Vec2& p) const {
    const auto clamp_to = [](double v, size_t n) { return std::min(n - 1, size_t(std::max(0.0, v))); };
    return clamp_to((p.y - origin_.y) / cell_, height_) * width_ + clamp_to((p.x - origin_.x) / cell_, width_);
}

Vec2 BoundaryDistance::centre(size_t x, size_t y) const {
    return origin_ + Vec2((double(x) + 0.5) * cell_, (double(y) + 0.5) * cell_);
}

void BoundaryDistance::sweep() {
    const long w = long(width_), h = long(height_);
    auto relax = [&](long x, long y, long nx, long ny) {
        if (nx < 0 || ny < 0 || nx >= w || ny >= h) return;
        const uint32_t cand = nearest_[size_t(ny * w + nx)];
        if (cand == UINT32_MAX) return;
        uint32_t& cur = nearest_[size_t(y * w + x)];
        const Vec2 m = centre(size_t(x), size_t(y));
        if (cur == UINT32_MAX || glm::length(samples_[cand].p - m) < glm::length(samples_[cur].p - m)) cur = cand;
    };
    for (long y = 0; y < h; ++y) {
        for (long x = 0; x < w; ++x)
            relax(x, y, x - 1, y), relax(x, y, x - 1, y - 1), relax(x, y, x, y - 1), relax(x, y, x + 1, y - 1);
        for (long x = w - 1; x >= 0; --x) relax(x, y, x + 1, y);
    }
    for (long y = h - 1; y >= 0; --y) {
        for (long x = w - 1; x >= 0; --x)
            relax(x, y, x + 1, y), relax(x, y, x + 1, y + 1), relax(x, y, x, y + 1), relax(x, y, x - 1, y + 1);
        for (long x = 0; x < w; ++x) relax(x, y, x - 1, y);
    }
}

double BoundaryDistance::operator()(const Vec2& p) const {
    if (samples_.empty()) return 0.0;
    const size_t c = cell_of(p);
    const long cx = long(c % width_), cy = long(c / width_);
    double best = 1e300;
    for (long y = cy - 1; y <= cy + 1; ++y) {
        for (long x = cx - 1; x <= cx + 1; ++x) {
            if (x < 0 || y < 0 || x >= long(width_) || y >= long(height_)) continue;
            const uint32_t s = nearest_[size_t(y) * width_ + size_t(x)];
            if (s != UINT32_MAX) best = std::min(best, segment_distance(p, samples_[s].a, samples_[s].b));
        }
    }
    return best;
}

}  // namespace body
