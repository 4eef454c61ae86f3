#pragma once
// The integer data textures of the line styles: `lines` reads one edge per
// texel (styles/lines.cpp), `wireframe` one vertex position (styles/
// wireframe.cpp), laid out kTextureWidth texels per row. A model keeps the
// data of one line style at a time.
#include <GLES3/gl3.h>

#include <cstddef>
#include <cstdint>

#include "kiosk/render/model.h"
#include "kiosk/render/programs.h"

namespace body::render {

// Texels per row of the data textures (the GLES 3.0 minimum); lines.vert and
// wireframe.vert hold it as a constant (a shift, not a division).
inline constexpr int kTextureWidth = 2048;

// An immutable texture of `capacity` texels, kTextureWidth per row, nearest filtering.
GLuint make_data_texture(GLenum internal, size_t capacity);

// Uploads elements [begin, end) of an array laid out kTextureWidth per row;
// `src` holds element `begin` first.
void texture_rows(GLuint tex, size_t begin, size_t end, GLenum format, GLenum type, const uint8_t* src,
                  size_t element_size);

// Binds `texture` to unit `unit` as the program's sampler `sampler`.
void bind_data_texture(Program& p, const char* sampler, GLuint texture, int unit);
// The dequantization of a data texture's 16-bit codes: object = origin + scale * code.
void set_quantization(Program& p, const Vec3f& origin, const Vec3f& scale);

// Frees the model's `wireframe` position textures / `lines` edge texture
// (marked stale, rebuilt from the GL buffers when the style returns) and
// trims the heap (software drivers keep textures in host memory).
void free_wire_textures(Model& m);
void free_edge_texture(Model& m);

}  // namespace body::render
