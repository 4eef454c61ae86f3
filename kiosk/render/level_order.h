#pragma once
// A settled level drawn in vertex-cache order: a progressive mesh's element
// buffer holds its live faces as a prefix in refinement order, which reuses
// the GPU's post-transform cache poorly (about twice the vertex work of a
// static mesh; bench/RESULTS.md, issue 24). Once a model's geometry has not
// changed for kSettleFrames frames and RendererOptions::settle_seconds, the
// prefix is copied on the GPU into a second element buffer, which stays
// mapped while the renderer's worker thread orders its triangles in place
// (window_order.h: corners untouched, so the winding stays); the frame that
// finds the job done unmaps it and the triangle styles draw from it until the
// geometry changes again, which frees it (the prefix is drawn meanwhile, as
// before). Vertices keep their order: a progressive mesh appends them.
//
// Only models uploaded with MeshData::order_settled_levels take part (a
// static mesh arrives ordered). The other readers of the element buffer
// (lines, wireframe, the cut section, picking) keep the prefix; a batch's
// element stream (batch.h) copies the ordered level.
// Memory: 4 bytes an index of the level in GL while ordered (12.8 MiB for
// 1.1M triangles); while the worker orders, a cell code a vertex (2 bytes)
// and one window's scratch (window_order.h; a few MiB, given back when done).
// Staged buffer access (discrete GPUs) orders in a staging buffer copied
// into the drawn one at the end. RendererOptions::settle_seconds < 0 turns
// ordering off.
//
// A model too large to batch (batch.h's kMaxBatchedVertices) with buffers
// mapped in place is ordered without the copy: its own element buffer is
// mapped between frames and ordered a slice a frame on the render thread
// (window_order.h's SlicedOrder; between slices it holds the level's
// triangles in some order, all drawable), keeping a permutation (packed:
// 21 bits a triangle at 1.1M, instead of the copy's 12 bytes) that puts the prefix back before the
// next change of its indices (restore_level_prefix, from update_model). Its
// other readers (lines, wireframe, the cut section, picking) then read the
// same triangles in that order.
#include <GLES3/gl3.h>

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>
#include <span>
#include <thread>
#include <vector>

#include "kiosk/render/window_order.h"

namespace body::render {

struct Model;

// Frames a model's geometry must stay unchanged before its level is ordered.
inline constexpr uint64_t kSettleFrames = 3;
// Levels below this many triangles are drawn from the prefix (ordering them
// would cost a job and a buffer for a draw that is cheap anyway).
inline constexpr size_t kMinOrderedTriangles = 1024;
// Triangle moves of a model ordered in place, a frame (SlicedOrder's budget:
// about four windows; 1.1M triangles take some 70 frames).
inline constexpr size_t kOrderSliceFaces = 32768;

class LevelOrderWorker;

// One ordering: the mapped copy of the level's indices (render thread), ordered
// in place (worker; nobody else touches them until `done`).
struct LevelOrderJob {
    std::span<uint32_t> indices;         // LevelOrder::pending, mapped
    std::vector<uint16_t> cells;         // window_order.h's cell of each vertex
    uint32_t version = 0;                // Model::geometry_version the prefix was copied at
    bool done = false;                   // under LevelOrderWorker's mutex
    bool ordered = false;                // set before `done`: the triangles are in cache order
    std::atomic<bool> dropped{false};    // the level changed: nobody takes the result
    LevelOrderWorker* worker = nullptr;  // the one it was submitted to
};

// A model's ordered level (Model::order).
struct LevelOrder {
    bool enabled = false;  // MeshData::order_settled_levels at add_model
    GLuint ebo = 0;        // the ordered faces of the level of `version`; 0: none
    uint32_t version = 0;
    size_t count = 0;  // index entries in ebo
    // When the geometry was last seen to change, in frames (render serial) and seconds.
    uint32_t seen_version = UINT32_MAX;
    uint64_t seen_frame = 0;
    double seen_seconds = 0.0;
    uint32_t tried_version = UINT32_MAX;  // the geometry a job was last started for
    std::shared_ptr<LevelOrderJob> job;   // in flight, or done and not yet taken
    GLuint pending = 0;                   // the job's buffer, mapped while it is ordered
    bool pending_staged = false;          // a staging buffer: copied into a new one at the end
    SlicedOrder sliced;                   // ordered in place (orders_in_place): the model's own buffer
};

// The renderer's worker thread, started at init (so that the kiosk's thread
// count stays as it was from the first frame on) and joined at shutdown.
class LevelOrderWorker {
public:
    ~LevelOrderWorker() { stop(); }
    void start();
    void submit(std::shared_ptr<LevelOrderJob> job);  // starts the thread if it is not running
    bool done(const LevelOrderJob& job);
    // No job queued or being ordered: levels are read back one at a time, so
    // a scene whose models settle together pays one read-back a frame and
    // holds one job's memory at a time.
    bool idle();
    void wait(const LevelOrderJob& job);
    // Drops `job` and returns once the worker no longer touches its indices
    // (at once if it is queued; the one in hand stops at its next window).
    void release(LevelOrderJob& job);
    void stop();  // the job in hand stops at its next window; queued ones are dropped

private:
    void run();
    std::mutex mutex_;
    std::condition_variable wake_, finished_;
    std::deque<std::shared_ptr<LevelOrderJob>> queue_;
    std::thread thread_;
    LevelOrderJob* current_ = nullptr;  // the job being ordered
    size_t pending_ = 0;                // submitted, not yet done or dropped
    bool stopping_ = false;
};

// Called once a frame per model before drawing (frame `serial`, at `seconds`
// on a steady clock): frees an ordered level the geometry has left, installs
// a finished job's result, and starts a job once the level has settled, the
// worker is idle and no other model was copied this frame (`read_back`,
// false at the frame's start, set when this one is).
void refresh_level_order(Model& m, LevelOrderWorker& worker, uint64_t serial, double seconds, double settle_seconds,
                         bool& read_back);
// The element buffer a triangle style draws `m` from: the ordered level when
// it is the current one, else the model's own (the prefix).
GLuint drawn_element_buffer(const Model& m);
// Whether `m`'s current level is one to order once it settles: a progressive
// model's (MeshData::order_settled_levels), of at least kMinOrderedTriangles,
// with ordering on (settle_seconds >= 0).
bool orders_level(const Model& m, double settle_seconds);
// Whether `m` draws its level from an ordered copy now.
bool level_ordered(const Model& m);
// Whether `m` is ordered in place (see the top): drawn alone, buffers mapped in place.
bool orders_in_place(const Model& m);
// Puts the prefix back into `m`'s element buffer when it was (partly) ordered
// in place, and forgets that order; false when the buffer could not be mapped
// or was lost while mapped (its contents are then undefined).
bool restore_level_prefix(Model& m);
// Bytes `m`'s order holds: its GL copy (and one being ordered), or its
// in-place order's permutation and working memory (capacities).
size_t level_order_bytes(const Model& m);
// Frees the ordered buffer and forgets the job (waits for the worker to let
// go of its mapped indices: at most one window).
void free_level_order(Model& m);

}  // namespace body::render
