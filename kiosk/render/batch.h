#pragma once
// Batched drawing: opaque `smooth` and `baseline` models drawn many per call, so that a scene of thousands of small
// structures costs per triangle, not per model (a software rasterizer pays tens of microseconds a draw call, and a
// board's driver a state validation).
//
// GLES 3.0 has neither a base vertex nor multi-draw, so models are gathered in chunks of up to slots_per_chunk: a chunk
// owns a copy of its members' vertex codes (positions as 16-bit codes in each model's box, normals as 8:8 octahedral
// codes, both copied buffer to buffer from the model's own) and a per-vertex slot number; each frame it draws one
// element stream per style: the index prefixes (the current level of detail) of its members on screen, offset to the
// chunk's vertices, nearest member first (a rasterizer then shades fewer hidden fragments; the order does not depend on
// the order the models arrived in). The stream is rebuilt (read back from the models' element buffers) only when its
// members, their styles or their levels change, or the camera turned by more than 15 degrees since its order. Each
// slot's model-view, normal matrix, position box and colour go to mesh.vert as one uniform array (BODY_BATCH); the
// arithmetic is the per-model path's, so a batched model draws the same pixels.
//
// A model is batched when it has at most kMaxBatchedVertices, is opaque (not selected or faded), in `smooth` or
// `baseline`, uploaded as position codes with normal codes, not gliding (geomorph) and no cut plane is on; everything
// else takes the per-model path (frame.cpp). Models join chunks at the frame that first sees them, filling the last
// chunk's free slots before a new chunk is made, and stay there; a removed model or one whose format changes leaves a
// dead slot. A slot has room for the vertices its model's own buffers hold (Model::vertex_allocated, grown with a
// streamed mesh), not its capacity: a scene of thousands of models drawn coarse would otherwise hold every model's full
// detail twice; a member that outgrows its room has the chunk laid out again (buffers reallocated, every member copied
// anew).
#include <GLES3/gl3.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kiosk/render/draw.h"
#include "kiosk/render/model.h"
#include "kiosk/render/programs.h"

namespace body::render {

struct RendererState;

// Models with more vertex capacity are drawn alone: their one draw call is
// nothing next to their triangles, and a chunk would hold a second copy of
// their vertex codes and of their level's indices (plus the stream's rebuild
// on the CPU at each change: +30 MiB peak for a 1.1M-triangle model on
// llvmpipe, bench/RESULTS.md).
inline constexpr size_t kMaxBatchedVertices = 65536;

// vec4s per slot in mesh.vert's u_slots: model-view (4), normal matrix (3),
// position origin and scale (2), colour (1).
inline constexpr int kBatchSlotVectors = 10;

struct BatchChunk {
    GLuint vao = 0, vbo_position = 0, vbo_normal = 0, vbo_slot = 0, ebo = 0;
    std::vector<Model*> members;           // by slot; null: dead (removed, or no longer codes)
    std::vector<size_t> vertex_base;       // by slot: first vertex in the chunk's buffers
    std::vector<size_t> vertex_room;       // by slot: vertices it has room for (relaid when one outgrows it)
    std::vector<uint64_t> copied_version;  // by slot: Model::geometry_version of the vertices copied
    size_t vertex_total = 0;
    // The element stream drawn last: what it was built from (slot, style,
    // index count and geometry version per member) and each style's range in it.
    std::vector<uint64_t> stream_key;
    Vec3f order_forward{0.0f};  // the camera's forward axis (world) when the stream's order was made
    size_t stream_entries = 0;
    size_t range_first[2] = {0, 0}, range_count[2] = {0, 0};  // smooth, baseline
};

struct Batches {
    bool enabled = false;
    int slots_per_chunk = 0;
    Program smooth, baseline;  // mesh.vert + smooth.frag / baseline.frag with BODY_BATCH
    std::vector<BatchChunk> chunks;
};

// Sets up the batch programs (linked at their first draw) when `on` and the driver has uniform room for at
// least 8 slots a chunk; batching stays off otherwise, and with BODY_BATCH=0
// in the environment (the per-model path, for comparisons).
Status init_batches(Batches& b, bool on);
void shutdown_batches(Batches& b);
// Whether `m` can be drawn in a batch this frame (see above; on screen is the caller's test).
bool batchable(const Frame& f, const Model& m, bool fade_rest);
// Draws the models of `drawn` (batchable ones, on screen) in their chunks,
// forming chunks for models that have none; counts them in s.stats. Returns
// the ones that left batching (their format is no longer codes) for the
// caller to draw per model.
std::vector<Model*> draw_batched(RendererState& s, Frame& f, const std::vector<Model*>& drawn);
// Forgets a removed model (its slot dies).
void forget_batched(RendererState& s, const Model& m);
// Bytes of the chunks' buffers.
size_t batch_gpu_bytes(const Batches& b);

}  // namespace body::render
