#pragma once
// The renderer's 16-bit position codes and packed normals, in one place (the
// GL formats of the model buffers and of the `lines` and `wireframe` data
// textures). mesh.vert, lines.vert and wireframe.vert decode them.
#include <cstdint>
#include <glm/gtc/type_precision.hpp>

#include "shared/geometry.h"

namespace body::render {

// A model buffer's code of p: round((p - origin) / scale) per axis, clamped to
// [0, 65535]; 0 on an axis whose scale is 0.
glm::u16vec3 position_code(const Vec3f& origin, const Vec3f& scale, const Vec3f& p);

// A data texture's code of one coordinate in a box: round((p - origin) /
// extent * 65535), clamped to [0, 65535]; 0 when the extent is 0.
uint16_t box_code(float p, float origin, float extent);

// A unit normal as GL_INT_2_10_10_10_REV (x low; w 0).
uint32_t pack_normal(const Vec3f& n);

// Unit vector -> 8:8 signed octahedral code, x in the low byte (Meyer et al.
// 2010, "On floating-point normal vectors"); lines.vert decodes it.
uint32_t pack_octahedral(const Vec3f& n);

// The .bpm's unsigned 8:8 octahedral codes (pm::oct_encode8 / oct_decode8),
// which mesh.vert decodes: the shared/pm coder, used through these two only.
void encode_normal_code(const Vec3f& n, uint8_t out[2]);
Vec3f decode_normal_code(const uint8_t code[2]);

}  // namespace body::render
