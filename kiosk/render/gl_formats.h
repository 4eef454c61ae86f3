#pragma once
// The renderer's 16-bit position codes and packed normals, in one place (the
// GL formats of the model buffers and of the `lines` and `wireframe` data
// textures). mesh.vert, lines.vert and wireframe.vert decode them.
#include <cstdint>
#include <glm/gtc/type_precision.hpp>

#include "shared/geometry.h"

namespace body::render {

// A model buffer's code of p: round((p - origin) / scale) per axis, clamped to
// [0, 65535]; 0 on an axis whose scale is 0. The exact inverse of mesh.vert's
// single-precision decode (origin + scale * code), so positions decoded from a
// model's codes (geomorph sources, patches) go back to the same codes; new
// codes are made by pm::quantize16 (the model files' and box_code's).
glm::u16vec3 position_code(const Vec3f& origin, const Vec3f& scale, const Vec3f& p);

// A data texture's code of one coordinate in the box [origin, origin + extent]:
// pm::quantize16 (the one quantizer); 0 when the extent is 0.
uint16_t box_code(float p, float origin, float extent);

// A unit normal as GL_INT_2_10_10_10_REV (x low; w 0).
uint32_t pack_normal(const Vec3f& n);

// The .bpm's 8:8 octahedral codes (pm::oct_encode8 / oct_decode8), the one
// normal code: mesh.vert and lines.vert decode it (shaders/normal_code.glsl).
// pack_normal_code: the two bytes in one word, x in the low byte.
uint32_t pack_normal_code(const Vec3f& n);
void encode_normal_code(const Vec3f& n, uint8_t out[2]);
Vec3f decode_normal_code(const uint8_t code[2]);

}  // namespace body::render
