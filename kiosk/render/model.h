#pragma once
// One uploaded model inside the renderer: its GL buffers and formats, drawn
// counts, bounds and the lazily built data textures of the line styles.
#include <GLES3/gl3.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "kiosk/render/level_order.h"
#include "kiosk/render/renderer.h"

namespace body::render {

struct Transfers;  // kiosk/render/buffer_access.h

struct Model {
    std::string name;
    Transfers* transfers = nullptr;  // the renderer's (add_model)
    ModelState state;
    GLuint vao = 0, vbo_position = 0, vbo_normal = 0, ebo = 0;
    GLuint vbo_morph = 0;  // geomorph sources (progressive meshes only)
    // Normals in GL: the source's 8:8 octahedral codes as they are (2 bytes a
    // vertex, decoded in mesh.vert) when add_model got codes, else
    // GL_INT_2_10_10_10_REV (4 bytes).
    bool normal_codes = false;
    size_t normal_stride() const { return normal_codes ? 2 : 4; }
    // Positions (and morph sources) in GL: 16-bit codes per axis in a box fixed
    // at add_model (object = pos_origin + pos_scale * code, 6 bytes a vertex),
    // or floats (12 bytes) when the box is not known or a patch left it.
    bool quantized = false;
    Vec3f pos_origin{0.0f}, pos_scale{1.0f};
    size_t position_stride() const { return quantized ? 6 : sizeof(Vec3f); }
    size_t vertex_capacity = 0, index_capacity = 0;
    // What the GL buffers hold now (<= the capacities; kiosk/render/buffer_growth.h).
    size_t vertex_allocated = 0, index_allocated = 0;
    size_t vertex_count = 0, index_count = 0;
    Vec3f center{0.0f};
    float radius = 0.0f;
    Vec3f box_min{0.0f}, box_max{0.0f};  // object space
    // Lazily created: the position texture for `wireframe`, the edge texture for `lines`
    // (kiosk/render/styles/wireframe.cpp, lines.cpp; a model keeps one at a time).
    // `wireframe`: x and y codes in RG16UI, z in R16UI (6 bytes a vertex; an
    // RGB16UI texture is padded to 8 by llvmpipe).
    GLuint position_texture = 0, position_texture_z = 0;
    Vec3f wire_origin{0.0f}, wire_scale{0.0f};  // dequantization of the position texture
    bool wire_stale = true;
    // `wireframe` where the driver offers buffer textures and the positions are
    // codes: an R16UI view of vbo_position (no storage of its own), attached
    // to the buffer named position_buffer_of when it held
    // position_buffer_vertices (a grown buffer is a new one, which may reuse
    // a deleted buffer's name).
    GLuint position_buffer_texture = 0, position_buffer_of = 0;
    size_t position_buffer_vertices = 0;
    GLuint edge_texture = 0;                    // RGBA32UI, one GpuEdge per texel
    Vec3f edge_origin{0.0f}, edge_scale{0.0f};  // dequantization of the GpuEdge endpoints
    size_t edge_capacity = 0;
    size_t edge_count = 0;
    bool edges_stale = true;
    bool internal = false;  // the manipulation sphere
    // Batched drawing (kiosk/render/batch.h): the chunk and slot (-1: none yet,
    // -2: never again).
    int batch_chunk = -1, batch_slot = -1;
    // Counts changes of the GL positions or indices (mesh_upload.cpp), so
    // copies and caches of the geometry (a batch chunk, the cut section) know when they are stale.
    uint32_t geometry_version = 0;
    // The cut plane's section of this model (styles/cut_cap.cpp), kept while
    // the object-space plane and the geometry stay as they were: the fan
    // triangles in `section_vbo` and the rectangle of the plane around them.
    GLuint section_vbo = 0;
    size_t section_vertices = 0, section_vbo_capacity = 0;
    bool section_valid = false;
    glm::vec4 section_plane{0.0f};  // object space
    uint32_t section_version = 0;
    Vec3f section_center{0.0f}, section_u{0.0f}, section_v{0.0f};  // object space, half sides
    // The settled level in vertex-cache order (kiosk/render/level_order.h).
    LevelOrder order;
};

// Deletes the model's GL buffers, vertex array and data textures.
void free_model(Model& m);

// World-space bounding sphere of a model (the largest axis scale of the transform).
void world_sphere(const Model& m, Vec3f& center, float& radius);

// How far in front of the camera (`view`) the model's bounding-sphere centre
// lies: the key that orders models front to back or back to front.
float view_depth(const Model& m, const glm::mat4& view);

}  // namespace body::render
