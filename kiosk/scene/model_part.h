#pragma once
// One structure of a scene model on the GPU: an OBJ object (ModelSource) or a
// structure of a .bpm being streamed (a pm::ProgressiveMesh owned by its
// model's StreamLoader, touched only under that loader's lock). Holds the
// renderer model it was uploaded as, moves it between levels of detail and
// picks against its current level.
//
// Level changes of a progressive part can glide (geomorph, in the vertex
// shader): the GPU's morph buffer holds the positions except, while a change
// glides, the vertices it adds or moves [morph_begin, morph_end), which hold
// where they are at the coarser of the two levels; the renderer draws
// mix(source, position, factor). A refinement glides 0 -> 1 at the new level;
// a coarsening glides 1 -> 0 and drops the level when it arrives. The CPU
// uploads the sources once when a glide starts and puts the positions back
// once when it stops; nothing per frame.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "kiosk/render/renderer.h"
#include "kiosk/scene/model_source.h"
#include "shared/geometry.h"
#include "shared/pm/progressive_mesh.h"

namespace body::kiosk {

// Geomorph timing: a level change blends over kSeconds instead of popping.
// factor() goes 0 -> 1 with a smoothstep.
class Geomorph {
public:
    static constexpr double kSeconds = 0.15;
    void start(double now, size_t from_triangles, size_t to_triangles);
    float factor(double now) const;
    bool active(double now) const { return started_ && now - start_ < kSeconds; }
    size_t from() const { return from_; }
    size_t to() const { return to_; }

private:
    bool started_ = false;
    double start_ = 0.0;
    size_t from_ = 0, to_ = 0;
};

class ModelPart {
public:
    explicit ModelPart(std::unique_ptr<ModelSource> source);  // OBJ object: no LOD hierarchy
    explicit ModelPart(pm::ProgressiveMesh& pm);              // streamed .bpm structure

    // Uploads the part (a streamed one: the levels decoded so far) as a renderer model named `name`.
    Status upload(render::Renderer& renderer, const std::string& name);
    render::ModelId id() const { return id_; }
    bool progressive() const { return pm_ != nullptr; }
    const ModelSource* source() const { return source_.get(); }
    const pm::ProgressiveMesh* pm() const { return pm_; }

    size_t full_triangles() const;
    size_t base_triangles() const;  // the coarsest level (OBJ: the full mesh)
    size_t triangles() const;       // at the current level
    // Object-space bounding sphere (a streamed structure's from its INFO box).
    bool bounds(const render::Renderer& renderer, Vec3f& center, float& radius) const;

    // Heads for the level `ratio` x full triangles gives (OBJ: the meshoptimizer
    // preview, only for a fixed ratio). `glide`: a progressive part geomorphs
    // there (call again each frame while gliding()); else it jumps. `streaming`:
    // its file is decoding now (not paused on demand), so it refines only in steps that at least
    // quadruple the triangles. Returns true when the part is at the level the
    // whole file would give for `ratio`.
    bool head_for(render::Renderer& renderer, double ratio, bool automatic, bool glide, bool streaming, double now);
    bool gliding() const { return morph_end_ > morph_begin_; }
    // Splits a streamed part must decode for the level `ratio` asks: what is
    // decoded when that reaches the ratio's triangles, else the last batch
    // boundary within them (estimated at the file's mean faces a split; a
    // batch past it would not be drawn), the whole file for full detail.
    size_t wanted_splits(double ratio) const;
    // The renderer's geomorph state for this part.
    void apply_morph(render::ModelState& state) const;
    // A complete progressive part with normals hands its index array to the
    // renderer (its element buffer becomes the only copy; picking reads it back).
    void hand_over_indices(render::Renderer& renderer);

    // Ray (world) against the current level placed by `transform`; world
    // distance. An OBJ's arrays are decoded for it and freed again.
    std::optional<float> pick(const render::Renderer& renderer, const glm::mat4& transform, const Ray& ray);
    // pick() for several world rays (unit directions) in one walk of the
    // triangles (ray_hits.h): nearest[k] lowered to ray k's world distance to
    // the part, if it hits nearer.
    void pick_many(const render::Renderer& renderer, const glm::mat4& transform, std::span<const Ray> rays,
                   std::span<float> nearest);

private:
    void upload_dirty(render::Renderer& renderer);
    void start_morph(render::Renderer& renderer, size_t lo, double now);
    void stop_morph(render::Renderer& renderer);
    void step_morph(render::Renderer& renderer, double now);
    void glide_to(render::Renderer& renderer, size_t level, double now);
    bool head_for_level(render::Renderer& renderer, double ratio, bool glide, bool streaming, double now);
    render::MeshData mesh() const;

    std::unique_ptr<ModelSource> source_;
    pm::ProgressiveMesh* pm_ = nullptr;
    render::ModelId id_ = 0;
    size_t base_triangles_ = 0;
    double source_ratio_ = 1.0;  // the OBJ preview's current ratio
    bool arrays_kept_ = false;   // the OBJ's float arrays are still held (released at head_for)
    Geomorph morph_;
    size_t morph_begin_ = 0, morph_end_ = 0;
    float morph_factor_ = 1.0f;
    bool collapsing_ = false;
    size_t pending_level_ = 0;
    std::vector<Vec3f> morph_sources_;  // working memory of start_morph, kept to avoid reallocating
    // head_for_level's last answer for a complete file: the ratio's triangles
    // (SIZE_MAX: none kept), its level and the level the whole file gives.
    size_t cached_want_ = SIZE_MAX, cached_level_ = 0, cached_wanted_full_ = 0;
};

}  // namespace body::kiosk
