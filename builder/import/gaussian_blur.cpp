// Separable Gaussian blur: three 1-D passes, one per axis (the Gaussian is the
// only rotationally symmetric separable kernel).
#include "builder/import/gaussian_blur.h"

#include <cassert>
#include <cmath>
#include <vector>

namespace body {
namespace {

std::vector<double> kernel(double sigma, size_t radius) {
    std::vector<double> k(2 * radius + 1);
    double sum = 0.0;
    for (size_t i = 0; i < k.size(); ++i) {
        const double d = static_cast<double>(i) - static_cast<double>(radius);
        k[i] = std::exp(-0.5 * d * d / (sigma * sigma));
        sum += k[i];
    }
    for (double& w : k) w /= sum;
    return k;
}

// Phase 1: one axis. Lines of `n` values `stride` apart start at every index
// whose coordinate along the axis is 0.
void blur_axis(std::span<float> field, const size_t size[3], int axis, const std::vector<double>& k,
               std::vector<double>& line) {
    const size_t radius = k.size() / 2;
    const size_t n = size[axis];
    const size_t strides[3] = {1, size[0], size[0] * size[1]};
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    const size_t stride = strides[axis], stride_a = strides[a], stride_b = strides[b];
    line.assign(n + 2 * radius, 0.0);
    for (size_t j = 0; j < size[b]; ++j) {
        for (size_t i = 0; i < size[a]; ++i) {
            float* p = field.data() + i * stride_a + j * stride_b;
            bool any = false;
            for (size_t t = 0; t < n; ++t) {
                line[radius + t] = p[t * stride];
                any |= p[t * stride] != 0.0f;
            }
            if (!any) continue;  // a zero line stays zero
            for (size_t t = 0; t < n; ++t) {
                double s = 0.0;
                for (size_t q = 0; q < k.size(); ++q) s += k[q] * line[t + q];
                p[t * stride] = static_cast<float>(s);
            }
        }
    }
}

}  // namespace

size_t gaussian_radius(double sigma) { return sigma > 0.0 ? static_cast<size_t>(std::ceil(3.0 * sigma)) : 0; }

void gaussian_blur_3d(std::span<float> field, const size_t size[3], const double sigma[3]) {
    assert(field.size() >= size[0] * size[1] * size[2]);
    std::vector<double> line;
    for (int axis = 0; axis < 3; ++axis) {
        if (sigma[axis] > 0.0) blur_axis(field, size, axis, kernel(sigma[axis], gaussian_radius(sigma[axis])), line);
    }
}

}  // namespace body
