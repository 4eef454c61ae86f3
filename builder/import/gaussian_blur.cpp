// Separable Gaussian blur: three 1-D passes, one per axis (the Gaussian is the
// only rotationally symmetric separable kernel). Along x each line is
// convolved from a copy; along y and z whole rows of x values are summed,
// weighted, so the inner loop runs over contiguous memory.
#include "builder/import/gaussian_blur.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <vector>

namespace body {
namespace {

std::vector<float> kernel(double sigma, size_t radius) {
    std::vector<double> k(2 * radius + 1);
    double sum = 0.0;
    for (size_t i = 0; i < k.size(); ++i) {
        const double d = static_cast<double>(i) - static_cast<double>(radius);
        k[i] = std::exp(-0.5 * d * d / (sigma * sigma));
        sum += k[i];
    }
    std::vector<float> out(k.size());
    for (size_t i = 0; i < k.size(); ++i) out[i] = static_cast<float>(k[i] / sum);
    return out;
}

// Phase 1: along x. The kernel is symmetric: pairs of taps share a weight.
// Each tap is added to the whole line before the next (the same sums, in the
// same order, per value), so the inner loop runs over contiguous values.
void blur_x(std::span<float> field, const size_t size[3], const std::vector<float>& k, std::vector<float>& line) {
    const size_t r = k.size() / 2, n = size[0];
    line.assign(n + 2 * r, 0.0f);
    for (size_t row = 0; row < size[1] * size[2]; ++row) {
        float* p = field.data() + row * n;
        if (std::all_of(p, p + n, [](float v) { return v == 0.0f; })) continue;  // a zero line stays zero
        std::copy(p, p + n, line.begin() + static_cast<long>(r));
        const float* c = line.data() + r;
        for (size_t t = 0; t < n; ++t) p[t] = k[r] * c[t];
        for (size_t q = 1; q <= r; ++q) {
            const float w = k[r + q];
            const float *before = c - q, *after = c + q;
            for (size_t t = 0; t < n; ++t) p[t] += w * (before[t] + after[t]);
        }
    }
}

// Phase 2: along y or z. `blocks` blocks of `n` rows of `len` values, rows
// contiguous within a block: each output row is the weighted sum of the input
// rows within the radius (zero rows skipped). Rows are taken in spans of at
// most kSpan values, so the copy stays small (a z pass's rows are whole planes).
void blur_rows(std::span<float> field, size_t blocks, size_t n, size_t len, const std::vector<float>& k,
               std::vector<float>& copy, std::vector<uint8_t>& nonzero) {
    constexpr size_t kSpan = 4096;
    const long r = static_cast<long>(k.size() / 2);
    const size_t span = std::min(len, kSpan);
    copy.resize(n * span);
    nonzero.resize(n);
    for (size_t b = 0; b < blocks; ++b) {
        for (size_t from = 0; from < len; from += span) {
            const size_t m = std::min(span, len - from);
            float* block = field.data() + b * n * len + from;
            bool any = false;
            for (size_t y = 0; y < n; ++y) {
                const float* row = block + y * len;
                nonzero[y] = std::any_of(row, row + m, [](float v) { return v != 0.0f; });
                any |= nonzero[y] != 0;
            }
            if (!any) continue;
            for (size_t y = 0; y < n; ++y) std::copy(block + y * len, block + y * len + m, copy.begin() + long(y * m));
            for (long y = 0; y < long(n); ++y) {
                float* out = block + y * long(len);
                std::fill(out, out + m, 0.0f);
                for (long q = std::max(-r, -y); q <= r && y + q < long(n); ++q) {
                    if (!nonzero[size_t(y + q)]) continue;
                    const float w = k[size_t(q + r)];
                    const float* in = copy.data() + (y + q) * long(m);
                    for (size_t i = 0; i < m; ++i) out[i] += w * in[i];
                }
            }
        }
    }
}

}  // namespace

size_t gaussian_radius(double sigma) { return sigma > 0.0 ? static_cast<size_t>(std::ceil(3.0 * sigma)) : 0; }

void gaussian_blur_3d(std::span<float> field, const size_t size[3], const double sigma[3]) {
    assert(field.size() >= size[0] * size[1] * size[2]);
    std::vector<float> line;
    std::vector<uint8_t> nonzero;
    if (sigma[0] > 0.0) blur_x(field, size, kernel(sigma[0], gaussian_radius(sigma[0])), line);
    if (sigma[1] > 0.0)
        blur_rows(field, size[2], size[1], size[0], kernel(sigma[1], gaussian_radius(sigma[1])), line, nonzero);
    if (sigma[2] > 0.0)
        blur_rows(field, 1, size[2], size[0] * size[1], kernel(sigma[2], gaussian_radius(sigma[2])), line, nonzero);
}

}  // namespace body
