#pragma once
// What Renderer::add_model and Renderer::update_model take: a mesh's arrays
// (or callbacks that write the GL buffers themselves) and the ranges changed
// since the last upload.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>

#include "shared/geometry.h"

namespace body::render {

// A mesh to upload: the first vertex_count positions (and normals, or empty to
// have area-weighted normals computed) and the first index_count indices
// (triangles, counter-clockwise from outside) are drawn. capacity_* (>= the
// counts; 0 = the span size) size the GL buffers for later growth.
struct MeshData {
    std::span<const Vec3f> positions;
    std::span<const Vec3f> normals;
    std::span<const uint32_t> indices;
    // Optional geomorph sources, one per position, uploaded with the same dirty
    // vertex ranges; their presence gives the model a morph buffer. At rest they
    // equal the positions (the kiosk passes the positions and patches a morph's
    // range with set_morph_sources, see pm::ProgressiveMesh::morph_sources);
    // see ModelState::morph.
    std::span<const Vec3f> morph_sources = {};
    size_t vertex_count = SIZE_MAX;  // SIZE_MAX: positions.size()
    size_t index_count = SIZE_MAX;   // SIZE_MAX: indices.size()
    // add_model only: the arrays are written up to vertex_count/index_count and
    // the rest is capacity for later update_model calls (a progressive mesh
    // still streaming). Only the counted prefix is read and uploaded, and the
    // buffers hold it, growing up to the arrays' size with later updates
    // (buffer_growth.h). False: the whole arrays are uploaded.
    bool prefix_only = false;
    // prefix_only: the vertices and index entries the model may grow to, when
    // more than the arrays hold now (a stream whose arrays grow with what it
    // decodes); later updates pass arrays up to that size. 0: the arrays' sizes.
    size_t vertex_capacity = 0, index_capacity = 0;
    // Optional box holding every position and morph source the model will
    // have (a progressive mesh's bounds). The renderer keeps positions as
    // 16-bit codes in a box (6 bytes a vertex instead of 12; exact for .bpm
    // positions, which are 16-bit codes in their box): this one, or without it
    // the box of the arrays when they are all written (not prefix_only); else
    // floats. A patch that leaves the box turns the model's positions to floats.
    bool has_position_box = false;
    Vec3f position_box_min{0.0f}, position_box_max{0.0f};
    // Optional, in place of `positions`: three 16-bit codes per vertex in the
    // position box (has_position_box needed), position = min + code * (max -
    // min) / 65535; uploaded as they are (a source that keeps its positions so
    // needs no float copy).
    std::span<const uint16_t> position_codes = {};
    // Optional, in place of `normals`: two 8-bit octahedral codes per vertex, as
    // a .bpm keeps them (pm::oct_decode8); packed for GL as they are uploaded.
    std::span<const uint8_t> normal_codes = {};
    // Without morph_sources: true gives the model a morph buffer holding its
    // positions (the sources at rest), patched with the same dirty vertex
    // ranges, so a source that keeps only codes needs no float copy.
    bool morph_at_rest = false;
    // Optional, for update_model in place of `indices` (left empty): a source
    // that keeps no index array of its own (the model's GL element buffer is
    // its only copy, e.g. a progressive mesh after
    // pm::ProgressiveMesh::release_indices) writes its changes straight into the
    // buffer's elements [index_patch_begin, index_patch_end), mapped for writing
    // (see BufferAccess: in place, no copy where the GPU shares memory with the
    // CPU, or staged): window[i] is element
    // first + i; entries it does not write keep their values. Its values are
    // trusted (the source's own, checked when it was read). Needs normals or
    // normal codes (area normals need the indices).
    std::function<void(std::span<uint32_t> window, size_t first)> index_patch = {};
    size_t index_patch_begin = 0, index_patch_end = 0;
    // Optional, for update_model in place of the positions and normals (both
    // left empty; has_position_box set to the box of the model's codes): a
    // source that keeps no vertex data of its own (pm::ProgressiveMesh::
    // release_vertex_data) XORs its position changes into the model's 16-bit
    // codes of the vertices [position_patch_begin, position_patch_end), mapped
    // for reading and writing (BufferAccess; window: 3 codes a vertex, first =
    // the first vertex); the normals do not change. Only for a model whose positions are codes in
    // that box and that has no morph buffer.
    std::function<void(std::span<uint16_t> window, size_t first)> position_patch = {};
    size_t position_patch_begin = 0, position_patch_end = 0;
    // Optional, add_model only, in place of `indices` (left empty; not with
    // prefix_only; needs normals or normal codes): a source that keeps its
    // index array packed fills the whole new element buffer of
    // index_fill_count entries, mapped for writing (BufferAccess), and frees
    // its copy.
    std::function<void(std::span<uint32_t> out)> index_fill = {};
    size_t index_fill_count = 0;
    // Optional, add_model only: told as `indices` go up in order (a piece at a
    // time) that the entries [0, end) are in the GL buffer, so a source handing
    // its array over for good can free it while it goes up (the two copies
    // never coexist in full). Not called for a prefix_only upload.
    std::function<void(size_t end)> indices_uploaded = {};
    // add_model only: the index prefix is a progressive mesh's (refinement
    // order), so a level that stays is drawn from an ordered copy
    // (kiosk/render/level_order.h).
    bool order_settled_levels = false;
};

// Half-open element ranges changed since the last upload (vertices: positions
// and normals; indices: index entries).
struct Dirty {
    size_t vertex_begin = 0, vertex_end = 0;
    size_t index_begin = 0, index_end = 0;
};

}  // namespace body::render
