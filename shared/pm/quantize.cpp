// See quantize.h.
#include "shared/pm/quantize.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace body::pm {

float dequantize16(uint16_t q, float lo, float hi) { return dequantize16(q, lo, quantization_step(lo, hi)); }

float float_at_or_below(double x) {
    const float f = float(x);
    return double(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

float float_at_or_above(double x) {
    const float f = float(x);
    return double(f) < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

void oct_encode8(double x, double y, double z, uint8_t out[2]) {
    const double l1 = std::fabs(x) + std::fabs(y) + std::fabs(z);
    if (!(l1 > 0.0)) {
        out[0] = out[1] = 128;
        return;
    }
    x /= l1;
    y /= l1;
    z /= l1;
    if (z < 0.0) {
        const double ox = (1.0 - std::fabs(y)) * (x < 0.0 ? -1.0 : 1.0);
        const double oy = (1.0 - std::fabs(x)) * (y < 0.0 ? -1.0 : 1.0);
        x = ox;
        y = oy;
    }
    const auto unorm8 = [](double v) {
        return uint8_t(std::clamp(std::nearbyint((v * 0.5 + 0.5) * 255.0), 0.0, 255.0));
    };
    out[0] = unorm8(x);
    out[1] = unorm8(y);
}

void oct_decode8(const uint8_t in[2], float out[3]) {
    // Single precision, branch-free (the decoder runs this once per vertex).
    float x = float(in[0]) * (2.0f / 255.0f) - 1.0f, y = float(in[1]) * (2.0f / 255.0f) - 1.0f;
    const float z = 1.0f - std::fabs(x) - std::fabs(y);
    const float t = std::max(-z, 0.0f);  // folding the lower hemisphere back
    x += x >= 0.0f ? -t : t;
    y += y >= 0.0f ? -t : t;
    const float l = 1.0f / std::sqrt(x * x + y * y + z * z);
    out[0] = x * l;
    out[1] = y * l;
    out[2] = z * l;
}

}  // namespace body::pm
