// The GL formats of the renderer's position codes and normals (contract in gl_formats.h).
#include "kiosk/render/gl_formats.h"

#include <algorithm>
#include <cmath>

#include "shared/pm/quantize.h"

namespace body::render {

glm::u16vec3 position_code(const Vec3f& origin, const Vec3f& scale, const Vec3f& p) {
    glm::u16vec3 c(0);
    for (int k = 0; k < 3; ++k)
        if (scale[k] > 0.0f)
            c[k] = static_cast<uint16_t>(std::lround(std::clamp((p[k] - origin[k]) / scale[k], 0.0f, 65535.0f)));
    return c;
}

uint16_t box_code(float p, float origin, float extent) {
    return extent > 0.0f ? pm::quantize16(p, origin, origin + extent) : uint16_t{0};
}

uint32_t pack_normal(const Vec3f& n) {
    auto q = [](float v) {
        int i = static_cast<int>(std::lround(std::clamp(v, -1.0f, 1.0f) * 511.0f));
        return static_cast<uint32_t>(i) & 0x3ffu;
    };
    return q(n.x) | (q(n.y) << 10) | (q(n.z) << 20);
}

uint32_t pack_normal_code(const Vec3f& n) {
    uint8_t c[2];
    encode_normal_code(n, c);
    return uint32_t{c[0]} | (uint32_t{c[1]} << 8);
}

void encode_normal_code(const Vec3f& n, uint8_t out[2]) { pm::oct_encode8(n.x, n.y, n.z, out); }

Vec3f decode_normal_code(const uint8_t code[2]) {
    float d[3];
    pm::oct_decode8(code, d);
    return Vec3f(d[0], d[1], d[2]);
}

}  // namespace body::render
