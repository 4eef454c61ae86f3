// The kiosk's start: the first frame with what is ready, the rest over the
// following frames (contract in scene_models.h: load_ready, upload_arrived).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "kiosk/scene/cut_volume_file.h"
#include "kiosk/scene/scene_models.h"

namespace body::kiosk {
namespace {

// Whether a loader has nothing more to wait for before its upload.
bool arrived(StreamLoader& loader) {
    auto guard = loader.lock();
    return loader.bases_ready() || loader.done();
}

float max_scale(const glm::mat4& t) {
    return std::max({glm::length(glm::vec3(t[0])), glm::length(glm::vec3(t[1])), glm::length(glm::vec3(t[2]))});
}

}  // namespace

// measure()'s sphere, over the INFO boxes (a part's sphere is its box's).
void SceneModels::summarize(size_t index) {
    PartSpheres spheres;
    ModelInfo mi;
    for (const pm::StructureSummary& s : models_[index].summary) {
        spheres.add(transforms_[index], scene_.models[index].transform.scale, (s.box_min + s.box_max) * 0.5f,
                    glm::length(s.box_max - s.box_min) * 0.5f);
        mi.full_triangles += s.full_triangles;
        mi.base_triangles += s.base_triangles;
    }
    spheres.finish(mi);
    info_[index] = mi;
}

size_t SceneModels::load_ready(render::Renderer& renderer, const LoadOptions& options) {
    renderer_ = &renderer;
    load_options_ = options;
    size_t n = 0;
    for (size_t i = 0; i < models_.size(); ++i) {
        Model& m = models_[i];
        if (m.loader && !m.summary.empty() && !arrived(*m.loader)) {
            m.pending = true;
            ++pending_count_;
            ++n;
            continue;
        }
        if (upload(i)) ++n;
    }
    load_cut_volume(scene_, renderer);
    return n;
}

size_t SceneModels::upload_arrived(std::chrono::steady_clock::time_point deadline) {
    for (size_t i = 0; i < models_.size() && pending_count_ > 0; ++i) {
        Model& m = models_[i];
        if (!m.pending || !arrived(*m.loader)) continue;
        m.pending = false;
        --pending_count_;
        upload(i);
        if (std::chrono::steady_clock::now() >= deadline) break;
    }
    return pending_count_;
}

void SceneModels::scene_bounds(const std::function<bool(size_t)>& visible,
                               const std::function<glm::mat4(size_t)>& placement, Vec3f& center, float& radius) const {
    std::vector<std::pair<Vec3f, float>> spheres;  // world
    for (size_t i = 0; i < models_.size(); ++i) {
        if (!visible(i)) continue;
        const glm::mat4 t = placement(i);
        const float s = max_scale(t);
        auto add = [&](Vec3f c, float r) { spheres.emplace_back(Vec3f(t * glm::vec4(c, 1.0f)), r * s); };
        if (models_[i].pending) {
            for (const pm::StructureSummary& p : models_[i].summary)
                add((p.box_min + p.box_max) * 0.5f, glm::length(p.box_max - p.box_min) * 0.5f);
            continue;
        }
        for (const ModelPart& p : models_[i].parts) {
            Vec3f c;
            float r = 0.0f;
            if (p.bounds(*renderer_, c, r)) add(c, r);
        }
    }
    // Renderer::scene_bounds' rule: the spheres' box centre, and the farthest sphere from it.
    Aabb box;
    for (const auto& [c, r] : spheres) {
        box.extend(Vec3(c - Vec3f(r)));
        box.extend(Vec3(c + Vec3f(r)));
    }
    center = box.empty() ? Vec3f(0.0f) : Vec3f((box.min + box.max) * 0.5);
    radius = 0.0f;
    for (const auto& [c, r] : spheres) radius = std::max(radius, glm::length(c - center) + r);
}

}  // namespace body::kiosk
