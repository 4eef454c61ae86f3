#pragma once
// The one path from a scene's model files to the GPU, shared by every bodyview
// mode (kiosk, screenshot, benchmark): loading (a model that fails is skipped
// with a logged reason), level of detail (a ratio of the full triangles ->
// a level, one rule for .bpm and OBJ), the binding of scene properties
// (colour, transform, style, visibility, selection) to the renderer's model
// states, and picking.
//
//   SceneModels models(scene);                 // .bpm files start decoding their base meshes
//   renderer.init();  models.load(renderer);   // uploads; skipped models are logged
//   models.release_detail(false);              // after the first frame (true: decode all now)
//   per frame: auto lock = models.lock(); models.poll_streams();
//              models.bind(i, binding, now) for each model; lock = {}; renderer.render(...)
//
// Threads: a .bpm streams on the shared decoding threads (scene/stream_loader.h,
// scene/decode_pool.h: cores - 1 of them, whatever the number of files), larger
// models first; its structures are touched only under lock(), which bind() and
// pick() need.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "kiosk/render/renderer.h"
#include "kiosk/scene/model_part.h"
#include "kiosk/scene/stream_loader.h"
#include "shared/geometry.h"
#include "shared/pm/bpm_summary.h"
#include "shared/scene/scene.h"

namespace body::kiosk {

// What is known of a loaded model, in scene space (after its transform).
struct ModelInfo {
    bool loaded = false;  // false: failed to load (skipped, never drawn or picked)
    glm::vec3 center{0.0f};
    float radius = 1.0f;
    size_t full_triangles = 0;
    size_t base_triangles = 0;
};

// A model's sphere in ModelInfo from its parts' spheres: each part's centre
// through the model matrix, its radius times the model's scale, the box around
// them all, and the sphere inscribed in that box's corners (loaded when any
// part was added). SceneModels measures uploaded parts and files' INFO boxes
// with it, so the two give the same sphere.
struct PartSpheres {
    glm::vec3 lo{1e30f}, hi{-1e30f};
    void add(const glm::mat4& transform, float scale, const Vec3f& center, float radius) {
        const glm::vec3 wc = glm::vec3(transform * glm::vec4(center, 1.0f));
        lo = glm::min(lo, wc - glm::vec3(radius * scale));
        hi = glm::max(hi, wc + glm::vec3(radius * scale));
    }
    void finish(ModelInfo& mi) const {
        mi.loaded = lo.x <= hi.x;
        mi.center = (lo + hi) * 0.5f;
        mi.radius = std::max(glm::length(hi - lo) * 0.5f / std::sqrt(3.0f), 1e-3f);
    }
};

// A scene transform as a model matrix (translate * Rz * Ry * Rx * scale: Euler
// X first, as SCENE.md says).
glm::mat4 to_model_matrix(const scene::Transform& transform);

// A model's properties for one frame.
struct ModelBinding {
    Style style = Style::Smooth;
    bool visible = true;
    bool selected = false;
    glm::mat4 transform{1.0f};   // object -> world
    double lod_ratio = 1.0;      // of the full triangles, in (0, 1]
    bool lod_automatic = false;  // chosen by the kiosk's LOD controller (OBJ: full detail)
    bool glide = true;           // geomorph level changes (false: jump, e.g. a screenshot)
    bool hold_level = false;     // keep the current level (the kiosk's first frame: base meshes)
    bool cut = true;             // the frame's cut plane applies (render::ModelState::cut)
};

struct LoadOptions {
    // A model shown alone (`--model`) keeps the colour its file gives, and the
    // renderer's default where the file gives none; else the manifest's colour.
    bool file_colours = false;
};

class SceneModels {
public:
    // Queues a loader for every .bpm at once (base meshes decode on the pool's
    // threads while the caller initialises the renderer).
    explicit SceneModels(const scene::Scene& scene);
    ~SceneModels();
    SceneModels(const SceneModels&) = delete;
    SceneModels& operator=(const SceneModels&) = delete;

    // Uploads every model (a .bpm once its base meshes are in). A model that
    // fails is logged ("bodyview: NAME: skipped: reason") and left out.
    // Returns how many models loaded.
    size_t load(render::Renderer& renderer, const LoadOptions& options = {});
    // The kiosk's start (scene/scene_loading.cpp): uploads the models whose base
    // meshes are in now and leaves every other .bpm pending, its ModelInfo
    // already filled from its file's INFO sections (read at construction), so
    // that the camera and the layout are final before any late model arrives.
    // A pending model draws nothing and picks nothing until upload_arrived()
    // uploads it. Returns how many models are loaded or pending.
    size_t load_ready(render::Renderer& renderer, const LoadOptions& options = {});
    // Without lock(), once a frame: uploads the pending models whose base meshes
    // have arrived (until `deadline`, at least one); a pending file that fails
    // is logged and skipped as load() does. Returns how many are still pending.
    size_t upload_arrived(std::chrono::steady_clock::time_point deadline);
    size_t pending() const { return pending_count_; }
    // The scene's bounds as Renderer::scene_bounds gives them once every model
    // is uploaded: the visible models' spheres under `placement`, a pending
    // model's from its INFO boxes.
    void scene_bounds(const std::function<bool(size_t)>& visible, const std::function<glm::mat4(size_t)>& placement,
                      Vec3f& center, float& radius) const;
    // The authoring mode's add and remove, after load(): the scene given to the
    // constructor has gained model `index` (inserted there) or lost it, and only
    // that model is uploaded or dropped; the others stay as they are. An
    // inserted .bpm is decoded whole before this returns (release_detail(true)).
    // A model that fails keeps its slot unloaded (info().loaded false) and the
    // reason is returned.
    Status insert_model(size_t index, const LoadOptions& options = {});
    void erase_model(size_t index);
    size_t size() const { return models_.size(); }
    const ModelInfo& info(size_t model) const { return info_[model]; }
    const std::vector<ModelInfo>& infos() const { return info_; }
    // A model's manifest transform as a matrix (to_model_matrix).
    const glm::mat4& transform(size_t model) const { return transforms_[model]; }
    const scene::Scene& scene() const { return scene_; }
    // The names of a model's structures (a file may hold several).
    std::vector<std::string> structure_names(size_t model) const;

    // Lets the loaders decode past the base meshes; `wait`: blocks until every
    // file is decoded (frames then do not depend on the machine's speed).
    void release_detail(bool wait);
    // Holds every streaming loader's lock (needed by bind() and pick()).
    std::vector<std::unique_lock<std::mutex>> lock() const;
    // Under lock(): notes streams that ended (logging why one ended early).
    // True while any model still decodes (a stream paused on demand does not).
    bool poll_streams();
    // Blocks until every stream has ended or paused, or `deadline` passed (gives the loaders the CPU).
    void wait_until(std::chrono::steady_clock::time_point deadline) const;

    // Under lock(): applies `binding` to every structure of `model` and heads
    // for its level of detail; a file still streaming is asked to decode as far
    // as that level needs (StreamLoader::want_splits), and no further. Returns
    // whether the model is at the detail the whole file would give (false while
    // decoding or gliding towards it).
    bool bind(size_t model, const ModelBinding& binding, double now);
    // Draws every structure of `model` in `colour` from now on (the authoring
    // mode's colour edits; the manifest's colour is applied at load).
    void set_colour(size_t model, const std::array<float, 3>& colour);
    // Triangles of a model at its current levels.
    size_t triangles(size_t model) const;
    // Under lock(): the ray's world distance to the model's surface placed by
    // `transform` (an OBJ's arrays are decoded for it and freed again).
    std::optional<float> pick(size_t model, const glm::mat4& transform, const Ray& ray);
    // Several rays at once (ModelPart::pick_many): nearest[k] lowered to ray k's hit distance.
    void pick_many(size_t model, const glm::mat4& transform, std::span<const Ray> rays, std::span<float> nearest);

private:
    // A scene model: its parts (a file may hold several structures) and, for a
    // .bpm, the loader still decoding its detail.
    struct Model {
        std::vector<ModelPart> parts;
        std::unique_ptr<StreamLoader> loader;
        bool streaming = false;
        bool pending = false;                       // load_ready(): bases not in yet
        std::vector<pm::StructureSummary> summary;  // the file's INFO sections (empty: unread or not a .bpm)
    };
    Status load_model(size_t index, const LoadOptions& options);
    void measure(size_t index);
    void summarize(size_t index);  // info_[index] from models_[index].summary
    // Uploads and measures model `index`, or logs why it is skipped and clears it; true when loaded.
    bool upload(size_t index);
    LoadOptions load_options_;

    size_t pending_count_ = 0;

    const scene::Scene& scene_;
    render::Renderer* renderer_ = nullptr;
    std::vector<Model> models_;
    std::vector<ModelInfo> info_;
    std::vector<glm::mat4> transforms_;
};

}  // namespace body::kiosk
