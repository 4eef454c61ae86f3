#pragma once
// BodyView's OpenGL ES 3.0 renderer (GLSL ES 3.00 only, no geometry shaders):
// the textbook styles of thesis section 3.4 per model, mixed depth-correctly in
// one frame. Shaped like Dear ImGui's OpenGL3 backend: init() / shutdown() /
// render() around one private state struct; each program is compiled at its
// first draw (a start compiles only what its first frame draws), a failed
// compile/link logged once with its info log and that program's draws skipped
// (GL errors, counted by the kiosk); debug builds (BODY_GL_DEBUG) check glGetError after
// each pass.
//
// Usage (the GLES 3 context of a platform::Surface must be current):
//   Renderer r;  r.init();
//   ModelId id = r.add_model({positions, normals, indices}, "liver").value();
//   r.state(id)->style = Style::Hatching;
//   r.render(view, lighting, frame);  surface->present();
//
// Models: positions/normals/indices are copied into GL buffers that hold what
// is written and grow up to the given arrays (their capacity; see MeshData and
// buffer_growth.h), then patched with update_model()
// and the dirty ranges of a progressive mesh (shared/pm), drawing the current
// prefixes vertex_count/index_count. Units are object space; ModelState::transform
// places a model in the world. The renderer keeps no CPU copy of the mesh: the
// `lines` style's edge texture (16 bytes per edge that can be drawn, positions
// and face normals inside; edges between faces of the same normal are left
// out) and `wireframe`'s position texture are built lazily from the GL
// buffers when a model is first drawn in that style, and a model keeps one of
// the two at a time (building one frees the other) and gives it back when
// its style changes to one that uses neither.
//
// Frame order: opaque models (any style), then transparent ones (selected =
// purple, x-ray/faded unselected) sorted back to front, each with a depth
// pre-pass so only its nearest layer blends. The white manipulation sphere of a
// selected model sits at its centre (opaque, seen through the purple).
//
// Inside (kiosk/render/): renderer.cpp init/shutdown and the model table
// around RendererState (renderer_state.h); programs.* the shader table;
// buffer_access.* mapping GL buffers; mesh_upload.cpp add_model/update_model;
// gl_formats.* the 16-bit codes and normal packings; frame.cpp render();
// styles/<style>.cpp each style's draw and data, next to kiosk/shaders/<style>.*.
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "kiosk/render/cut_plane.h"
#include "kiosk/render/mesh_data.h"
#include "kiosk/render/view.h"
#include "shared/error.h"
#include "shared/geometry.h"
#include "shared/style.h"

namespace body {
struct SliceVolume;  // shared/scene/slice_volume.h
}  // namespace body

namespace body::render {

using ModelId = uint32_t;

struct ModelState {
    Style style = Style::Smooth;
    Vec3f color{0.85f, 0.62f, 0.55f};
    glm::mat4 transform{1.0f};  // object -> world
    bool visible = true;
    bool selected = false;  // transparent purple + the white manipulation sphere
    // Geomorph, done in the vertex shader: vertices [morph_begin, vertex_count)
    // are drawn at mix(morph source, position, morph); the others (and models
    // uploaded without morph sources) at their positions. morph = 1: no morph.
    // The `lines` and `wireframe` styles draw the positions as they are.
    size_t morph_begin = SIZE_MAX;
    float morph = 1.0f;
    bool cut = true;  // FrameOptions::cut applies to this model (a group may be cut alone)
};

// Lights are attached to the camera: directions in view space, toward the light.
struct Lighting {
    Vec3f key_dir{-0.45f, 0.55f, 0.70f};
    Vec3f fill_dir{0.65f, -0.15f, 0.55f};
    Vec3f rim_dir{0.0f, 0.4f, -1.0f};
    float key = 0.80f, fill = 0.22f, rim = 0.35f, ambient = 0.12f;
};

struct FrameOptions {
    int width = 0, height = 0;  // viewport in pixels
    unsigned framebuffer = 0;   // platform::Surface::framebuffer()
    Vec3f background{0.97f, 0.96f, 0.93f};
    Vec3f paper{1.0f, 1.0f, 0.99f};  // `lines` fill
    Vec3f ink{0.10f, 0.09f, 0.09f};  // `lines` edges
    Vec3f selection_color{0.50f, 0.18f, 0.80f};
    float line_width_px = 2.0f;      // silhouettes; creases 0.7x, wireframe 1x
    float crease_angle_deg = 45.0f;  // dihedral angle above which an edge is a crease
    bool xray_unselected = false;    // fade everything not selected (when something is)
    bool manipulation_sphere = true;
    float sphere_fraction = 0.2f;  // manipulation sphere radius / model bounding radius
    CutPlane cut;                  // kiosk/render/cut_plane.h; needs a stencil buffer for the caps
};

struct FrameStats {
    size_t models_drawn = 0, triangles = 0, edges = 0, draw_calls = 0;
    // Cut sections found on the CPU this frame (styles/cut_cap.h); a model
    // whose plane and geometry stayed keeps its section from an earlier frame.
    size_t cut_sections = 0;
    // Milliseconds this frame spent reading levels back for ordering and
    // uploading ordered ones (kiosk/render/level_order.h; the ordering itself
    // runs on a worker).
    double level_order_ms = 0.0;
    // Programs linked by this frame: each is linked at its first draw.
    size_t programs_linked = 0;
};

// How the renderer writes into its GL buffers (a progressive mesh's packed
// index fill and level-change patches) and reads them back (the `lines` edge
// list and the `wireframe` positions, picking): GLES 3.0 can only map them.
enum class BufferAccess {
    // Staged on the drivers of GPUs with memory of their own (GL_VENDOR
    // NVIDIA, AMD or ATI), in place elsewhere.
    Auto,
    // The model's buffer is mapped: no copy where the GPU shares memory with
    // the CPU (Raspberry Pi-class boards, Mesa's software rasterizers).
    InPlace,
    // A map that writes goes through a temporary buffer: the range is copied
    // into it on the GPU, mapped there, copied back and the buffer deleted, so
    // the model's buffer is never mapped for writing (a discrete GPU's driver
    // draws such a buffer from host memory for a while after; bench/RESULTS.md).
    // Reads map in place.
    Staged,
};
const char* buffer_access_name(BufferAccess access);  // "auto", "in-place", "staged"
Result<BufferAccess> parse_buffer_access(const std::string& name);

struct RendererOptions {
    BufferAccess buffer_access = BufferAccess::Auto;
    // Opaque smooth and baseline models drawn many per call (kiosk/render/batch.h);
    // false (or BODY_BATCH=0 in the environment): one call a model.
    bool batch = true;
    // `wireframe` reads quantized positions through a buffer texture over the
    // position buffer where the context is GLES 3.2 (styles/wireframe.cpp);
    // false: the position textures every context can use (GLES 3.0/3.1 boards).
    bool wire_buffer_texture = true;
    // A progressive model's level that stays this long (and kSettleFrames
    // frames) is drawn from a copy in vertex-cache order (level_order.h);
    // negative: never (the copy and its making cost memory, see there).
    double settle_seconds = 0.25;
};

// What buffer reads and writes moved since init (tests, the benchmark).
struct TransferStats {
    size_t in_place_maps = 0;    // model buffers mapped in place (reads and writes)
    size_t in_place_writes = 0;  // of which mapped for writing
    size_t staged_bytes = 0;     // bytes copied through temporary buffers, each way counted
};

struct RendererState;

class Renderer {
public:
    Renderer();
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Sets up the state (shaders are compiled at their first draw, the tonal art map at the first hatching
    // draw). Needs a current GLES 3 context.
    Status init(const RendererOptions& options = {});
    // The access init() chose (never Auto after a successful init).
    BufferAccess buffer_access() const;
    const TransferStats& transfer_stats() const;
    // Frees every GL object (call with the context current). Idempotent.
    void shutdown();

    // Uploads a mesh; errors (out-of-range index, empty mesh) name `name`.
    Result<ModelId> add_model(const MeshData& mesh, const std::string& name);
    // Patches the ranges of `mesh` named by `dirty` and sets the drawn counts.
    // The arrays must be the full arrays (dirty ranges index into them).
    Status update_model(ModelId id, const MeshData& mesh, const Dirty& dirty);
    // Overwrites the geomorph sources [begin, begin + sources.size()) of a model
    // uploaded with morph_sources (a morph starting or ending); see ModelState::morph.
    Status set_morph_sources(ModelId id, size_t begin, std::span<const Vec3f> sources);
    void remove_model(ModelId id);
    // nullptr for an unknown id.
    ModelState* state(ModelId id);
    const ModelState* state(ModelId id) const;
    std::vector<ModelId> models() const;
    // Object-space bounding sphere of the uploaded vertices.
    bool bounds(ModelId id, Vec3f& center, float& radius) const;
    // Calls `read` with the model's index entries [0, count), read back from
    // its element buffer (mapped for reading, in place in either BufferAccess),
    // for sources that handed their array over (MeshData::index_patch). False,
    // without calling it, for an unknown model, a count past the buffer or a
    // failed mapping. Context current.
    bool read_indices(ModelId id, size_t count, const std::function<void(std::span<const uint32_t>)>& read) const;
    // Whether the model draws its current level from a copy in vertex-cache
    // order (MeshData::order_settled_levels, kiosk/render/level_order.h).
    bool level_ordered(ModelId id) const;
    // Whether it will once its level stays (a progressive model's level of at
    // least kMinOrderedTriangles).
    bool orders_level(ModelId id) const;
    // Waits for the orderings in flight (for the benchmark and tests; the
    // kiosk never waits); the next frame draws their results.
    void finish_level_orders();
    // Bytes the settled-level orders hold now (level_order.h): GL copies of
    // ordered levels, permutations of levels ordered in place, and their working memory.
    size_t level_order_bytes() const;
    // Like read_indices, the ordered copy's entries; false when the model
    // draws no ordered level now.
    bool read_ordered_indices(ModelId id, const std::function<void(std::span<const uint32_t>)>& read) const;
    // The model's vertex positions [0, vertex count) read back from its
    // position buffer (floats, or codes decoded as mesh.vert decodes them),
    // for CPU readers of a source that handed its vertex data over
    // (pm::ProgressiveMesh::release_vertex_data). False, with `out` empty, for
    // an unknown model or a failed mapping. Context current.
    bool read_positions(ModelId id, std::vector<Vec3f>& out) const;
    // World-space bounding sphere of all visible models (radius 0 when none).
    void scene_bounds(Vec3f& center, float& radius) const;
    // World-space bounding box of all visible models; false when none.
    bool scene_box(Vec3f& lo, Vec3f& hi) const;

    // Draws one frame into options.framebuffer.
    void render(const View& view, const Lighting& lighting, const FrameOptions& options);
    const FrameStats& last_frame_stats() const;
    // Draws a few frames of the smallest model, cut and capped in every style and
    // selected, into options.framebuffer (the next frame overwrites them), so that
    // the driver compiles the cut plane's shader variants now (the kiosk: after
    // its first frame) rather than at a visitor's first cut. Model states are restored.
    void warm_up_cut(const Lighting& lighting, const FrameOptions& options);
    // The grey-level volume shown on the cut plane's caps (kiosk/render/cut_volume.h);
    // nullptr removes it. Errors (a dimension over GL_MAX_3D_TEXTURE_SIZE, a
    // refused texture) leave no volume. Context current.
    Status set_cut_volume(const SliceVolume* volume);
    // Bytes of GL buffers and textures this renderer created (models, lazily
    // built edge lists and data textures, the tonal art map).
    size_t gpu_bytes() const;

private:
    std::unique_ptr<RendererState> s_;  // kiosk/render/renderer_state.h
};

// Embedded GLSL sources (kiosk/shaders/, generated into the build at compile
// time); nullptr for an unknown name such as "smooth.frag".
const char* shader_source(const std::string& name);

// Compiles and links one GLSL ES 3.00 program (the renderer's and the kiosk
// overlay's), binding the named attribute locations before linking, or loads
// the binary kept for the same sources (program_binary.h); a context must be
// current. Errors name `name` and carry the info log on one line.
Result<unsigned> link_program(const char* vertex_source, const char* fragment_source, const std::string& name,
                              std::span<const std::pair<unsigned, const char*>> attributes = {});

}  // namespace body::render
