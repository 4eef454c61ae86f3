#pragma once
// A model's GL buffers grown as its data arrives instead of sized to its
// capacity at add_model: a progressive mesh still streaming has only its base
// level written, and a kiosk under automatic LOD may never draw more of it, so
// buffers at full capacity (which llvmpipe clears at once) would cost the
// first frame their page faults and the process their memory for data never
// uploaded. Model::vertex_capacity / index_capacity stay the limits an upload
// is checked against; Model::vertex_allocated / index_allocated are what the
// GL buffers hold.
//
// Growth: to the count asked for, at least double the current size, at most
// the capacity; a new buffer, the old contents copied on the GPU
// (glCopyBufferSubData), the old one deleted and the model's vertex array
// pointed at the new one. Contents and pictures stay the same.
#include <GLES3/gl3.h>

#include <cstddef>

#include "kiosk/render/model.h"

namespace body::render {

// Makes the vertex buffers (positions, normals, morph sources) hold at least
// `count` vertices (at most the capacity). Binds vertex array 0.
void reserve_vertices(Model& m, size_t count);
// Makes the element buffer hold at least `count` entries (at most the capacity). Binds vertex array 0.
void reserve_indices(Model& m, size_t count);

// The position (or morph) attribute of the model's format, from the GL_ARRAY_BUFFER bound.
void position_pointer(const Model& m, GLuint location);
// The normal attribute of the model's format (Model::normal_codes), from the GL_ARRAY_BUFFER bound.
void normal_pointer(const Model& m);

}  // namespace body::render
