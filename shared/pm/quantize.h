#pragma once
// The one position quantizer and the one normal coder: 16-bit codes per axis in
// a float box [lo, hi], q = nearbyint((x - lo) / (hi - lo) * 65535) (ties to
// even), and 8:8 octahedral normals (Meyer et al. 2010; unsigned codes, 128 the
// middle). The `.bpm` writer, the simplifier's grid check and the reader use
// these, and so should any other code that makes or reads such codes.
// Double arithmetic without floating-point contraction (cmake/warnings.cmake):
// the same codes on every platform.
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace body::pm {

inline constexpr uint32_t kMaxCode16 = 65535;  // codes 0 .. kMaxCode16 span [lo, hi]

// The nearest float at or below / at or above x. An axis whose positions span [min, max]
// is quantized in [lo, hi] = [float_at_or_below(min), float_at_or_above(max)].
float float_at_or_below(double x);
float float_at_or_above(double x);
// The distance between adjacent codes in [lo, hi]. Two values at least this far apart
// always get different codes (rounding is monotonic).
inline double quantization_step(float lo, float hi) { return (double(hi) - double(lo)) / 65535.0; }
// The quantizer: at most half a step from x; 0 for an empty box.
inline uint16_t quantize16(double x, float lo, float hi) {
    const double range = double(hi) - double(lo);
    if (!(range > 0.0)) return 0;
    const double t = std::nearbyint((x - double(lo)) / range * 65535.0);
    return uint16_t(std::clamp(t, 0.0, 65535.0));
}
// The position of code q: lo + q * step (double, rounded to float once).
float dequantize16(uint16_t q, float lo, float hi);
// The same with step = quantization_step(lo, hi) computed once (same result).
inline float dequantize16(uint16_t q, float lo, double step) { return float(double(lo) + double(q) * step); }
// The unit vector of an octahedral code (single precision).
void oct_decode8(const uint8_t in[2], float out[3]);
// Each code nearbyint((u * 0.5 + 0.5) * 255) of the folded L1-normalised vector
// (x, y, z < 0 folded over the diagonals). Any nonzero vector (normalized by its L1 norm); the zero vector gives (128,
// 128).
void oct_encode8(double x, double y, double z, uint8_t out[2]);

}  // namespace body::pm
