#pragma once
// A settled level drawn in vertex-cache order: a progressive mesh's element
// buffer holds its live faces as a prefix in refinement order, which reuses
// the GPU's post-transform cache poorly (about twice the vertex work of a
// static mesh; bench/RESULTS.md, issue 24). Once a model's geometry has not
// changed for kSettleFrames frames and RendererOptions::settle_seconds, its
// prefix is read back once and handed to the renderer's worker thread, which
// orders the same triangles (corners untouched, so the winding stays) with
// meshopt_optimizeVertexCache; the next frame uploads the result to a second
// element buffer and the triangle styles draw from it until the geometry
// changes again, which frees it (the prefix is drawn meanwhile, as before).
// Vertices keep their order: a progressive mesh appends them.
//
// Only models uploaded with MeshData::order_settled_levels take part (a
// static mesh arrives ordered). The other readers of the element buffer
// (lines, wireframe, the cut section, picking) keep the prefix; a batch's
// element stream (batch.h) copies the ordered level.
// Memory: 4 bytes an index of the level in GL while ordered (12.8 MiB for
// 1.1M triangles); while the worker orders, the copy in and out plus
// meshoptimizer's scratch (about 48 bytes a triangle and 16 a vertex: some
// 50 MiB for 1.1M triangles, given back when done; bench/RESULTS.md).
// RendererOptions::settle_seconds < 0 turns ordering off.
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

namespace body::render {

struct Model;

// Frames a model's geometry must stay unchanged before its level is ordered.
inline constexpr uint64_t kSettleFrames = 3;
// Levels below this many triangles are drawn from the prefix (ordering them
// would cost a job and a buffer for a draw that is cheap anyway).
inline constexpr size_t kMinOrderedTriangles = 1024;

// One ordering: the level's indices in (render thread), ordered out (worker).
struct LevelOrderJob {
    std::vector<uint32_t> indices;
    size_t vertex_count = 0;
    uint32_t version = 0;              // Model::geometry_version the prefix was read at
    bool done = false;                 // under LevelOrderWorker's mutex
    std::atomic<bool> dropped{false};  // the level changed: nobody takes the result
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
    void stop();  // waits for the job in hand; queued ones are dropped

private:
    void run();
    std::mutex mutex_;
    std::condition_variable wake_, finished_;
    std::deque<std::shared_ptr<LevelOrderJob>> queue_;
    std::thread thread_;
    size_t pending_ = 0;  // submitted, not yet done or dropped
    bool stopping_ = false;
};

// The triangles of `indices` (a whole number of them, every index below
// vertex_count) in meshoptimizer's vertex cache order, each triangle's
// corners as they were.
std::vector<uint32_t> order_level(std::span<const uint32_t> indices, size_t vertex_count);

// Called once a frame per model before drawing (frame `serial`, at `seconds`
// on a steady clock): frees an ordered level the geometry has left, installs
// a finished job's result, and starts a job once the level has settled, the
// worker is idle and no other model was read back this frame (`read_back`,
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
// Frees the ordered buffer and forgets the job (the worker drops its result).
void free_level_order(Model& m);

}  // namespace body::render
