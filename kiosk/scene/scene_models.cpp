// A scene's models on the GPU (contract in scene_models.h).
#include "kiosk/scene/scene_models.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "kiosk/scene/cut_volume_file.h"

namespace body::kiosk {

glm::mat4 to_model_matrix(const scene::Transform& t) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(t.translate[0], t.translate[1], t.translate[2]));
    m = glm::rotate(m, glm::radians(t.rotate_deg[2]), glm::vec3(0, 0, 1));
    m = glm::rotate(m, glm::radians(t.rotate_deg[1]), glm::vec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(t.rotate_deg[0]), glm::vec3(1, 0, 0));
    return glm::scale(m, glm::vec3(t.scale));
}

namespace {
// What a model covers on screen, estimated before anything of it is read (the
// decoding order needs it before the bounds are known): its file's bytes grow
// with its triangles, which grow with its surface at the atlas's resolution,
// and the manifest's scale enlarges that surface by its square.
double screen_size_estimate(const scene::Model& m) {
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(m.path, ec);
    return ec ? 0.0 : static_cast<double>(bytes) * double(m.transform.scale) * double(m.transform.scale);
}

// std::filesystem::path(path).extension() == ".bpm" without building a path
// (its parse was a third of the start's per-model cost on 2,000 models): the
// file name's last dot, not its first character, starts ".bpm".
bool is_bpm(const std::string& path) {
    const size_t name = path.find_last_of('/') + 1;  // 0 without a slash
    const size_t dot = path.rfind('.');
    return dot != std::string::npos && dot > name && path.compare(dot, std::string::npos, ".bpm") == 0;
}
}  // namespace

SceneModels::SceneModels(const scene::Scene& scene)
    : scene_(scene), models_(scene.models.size()), info_(scene.models.size()) {
    for (const scene::Model& m : scene.models) transforms_.push_back(to_model_matrix(m.transform));
    // Every file's INFO sections first (no decoding): their bounds order the
    // decoding by size on screen (the world radius; unreadable ones last).
    for (size_t i = 0; i < scene.models.size(); ++i) {
        const scene::Model& m = scene.models[i];
        if (!is_bpm(m.path)) continue;
        if (auto summary = pm::read_bpm_summary(m.path)) {
            models_[i].summary = std::move(summary).value();
            summarize(i);
        }
    }
    for (size_t i = 0; i < scene.models.size(); ++i) {
        const scene::Model& m = scene.models[i];
        if (!is_bpm(m.path)) continue;
        const double priority = info_[i].loaded ? double(info_[i].radius) : 0.0;
        // On demand: past the bases only what bind()'s levels want (the kiosk's memory follows what it draws).
        models_[i].loader = std::make_unique<StreamLoader>(m.path, 64 * 1024, priority, DecodePool::shared(), true);
    }
}

SceneModels::~SceneModels() = default;

namespace {

// Notes, under the loader's lock, that a stream has ended, logging why when it
// ended early (what arrived before stays usable).
void check_stream(StreamLoader& loader, bool& streaming, const std::string& name) {
    if (!streaming || !loader.done()) return;
    streaming = false;
    if (!loader.error().empty())
        std::fprintf(stderr, "bodyview: %s: %s (keeping what arrived)\n", name.c_str(), loader.error().c_str());
}

// The parts of a .bpm whose base meshes are in (under the loader's lock).
Status stream_parts(StreamLoader& loader, std::vector<ModelPart>& parts) {
    if (!loader.bases_ready()) {
        const std::string& why = loader.error();
        return input_error(why.empty() ? loader.path() + ": ended before every base mesh arrived" : why);
    }
    pm::BpmStream& stream = loader.stream();
    for (size_t i = 0; i < stream.structure_count(); ++i) parts.emplace_back(stream.structure(i));
    return ok_status();
}

Status file_parts(const std::string& path, std::vector<ModelPart>& parts) {
    auto sources = load_model_file(path);
    if (!sources) return sources.error();
    for (auto& src : sources.value()) parts.emplace_back(std::make_unique<ModelSource>(std::move(src)));
    return ok_status();
}

// The colour a part is drawn in: the manifest's, or with file_colours the file's
// own (none where it has the default grey: the renderer's default stays).
std::optional<Vec3f> part_colour(const ModelPart& part, const scene::Model& m, const LoadOptions& options) {
    if (!options.file_colours) return Vec3f(m.colour[0], m.colour[1], m.colour[2]);
    const Vec3f c = part.pm() ? part.pm()->color() : part.source()->color();
    if (c == Vec3f(0.8f)) return std::nullopt;
    return c;
}

}  // namespace

Status SceneModels::load_model(size_t index, const LoadOptions& options) {
    const scene::Model& m = scene_.models[index];
    Model& model = models_[index];
    std::unique_lock<std::mutex> stream_lock;
    if (model.loader) {
        model.loader->wait_for_bases();
        stream_lock = model.loader->lock();
        if (auto s = stream_parts(*model.loader, model.parts); !s) return s;
        model.streaming = true;
        check_stream(*model.loader, model.streaming, m.name);  // a file that failed after its bases: show them
    } else if (auto s = file_parts(m.path, model.parts); !s) {
        return s;
    }
    if (model.parts.empty()) return input_error(m.path + ": no structures");
    for (ModelPart& p : model.parts) {
        if (auto s = p.upload(*renderer_, m.name); !s) return s;
        if (auto c = part_colour(p, m, options)) renderer_->state(p.id())->color = *c;
    }
    return ok_status();
}

void SceneModels::set_colour(size_t model, const std::array<float, 3>& colour) {
    for (ModelPart& p : models_[model].parts)
        if (render::ModelState* st = renderer_ ? renderer_->state(p.id()) : nullptr)
            st->color = Vec3f(colour[0], colour[1], colour[2]);
}

// The world bounding sphere and triangle counts over a model's parts.
void SceneModels::measure(size_t index) {
    PartSpheres spheres;
    ModelInfo& mi = info_[index];
    mi = ModelInfo{};
    for (const ModelPart& p : models_[index].parts) {
        Vec3f c;
        float r = 0.0f;
        if (!p.bounds(*renderer_, c, r)) continue;
        spheres.add(transforms_[index], scene_.models[index].transform.scale, c, r);
        mi.full_triangles += p.full_triangles();
        mi.base_triangles += p.base_triangles();
    }
    spheres.finish(mi);
}

bool SceneModels::upload(size_t i) {
    if (Status st = load_model(i, load_options_); !st) {
        std::fprintf(stderr, "bodyview: %s: skipped: %s\n", scene_.models[i].name.c_str(), st.error().message.c_str());
        for (ModelPart& p : models_[i].parts)
            if (p.id()) renderer_->remove_model(p.id());
        models_[i] = Model{};
        info_[i] = ModelInfo{};
        return false;
    }
    measure(i);
    return info_[i].loaded;
}

size_t SceneModels::load(render::Renderer& renderer, const LoadOptions& options) {
    renderer_ = &renderer;
    load_options_ = options;
    size_t ok = 0;
    for (size_t i = 0; i < models_.size(); ++i)
        if (upload(i)) ++ok;
    load_cut_volume(scene_, renderer);
    return ok;
}

Status SceneModels::insert_model(size_t index, const LoadOptions& options) {
    const scene::Model& m = scene_.models[index];
    models_.insert(models_.begin() + static_cast<std::ptrdiff_t>(index), Model{});
    info_.insert(info_.begin() + static_cast<std::ptrdiff_t>(index), ModelInfo{});
    transforms_.insert(transforms_.begin() + static_cast<std::ptrdiff_t>(index), to_model_matrix(m.transform));
    if (is_bpm(m.path))
        models_[index].loader = std::make_unique<StreamLoader>(m.path, 64 * 1024, screen_size_estimate(m));
    if (Status st = load_model(index, options); !st) {
        for (ModelPart& p : models_[index].parts)
            if (p.id()) renderer_->remove_model(p.id());
        models_[index] = Model{};
        return st;
    }
    measure(index);
    if (models_[index].loader) models_[index].loader->wait_until_done();
    return ok_status();
}

void SceneModels::erase_model(size_t index) {
    for (ModelPart& p : models_[index].parts)
        if (p.id()) renderer_->remove_model(p.id());
    models_.erase(models_.begin() + static_cast<std::ptrdiff_t>(index));
    info_.erase(info_.begin() + static_cast<std::ptrdiff_t>(index));
    transforms_.erase(transforms_.begin() + static_cast<std::ptrdiff_t>(index));
}

std::vector<std::string> SceneModels::structure_names(size_t model) const {
    std::vector<std::string> names;
    for (const ModelPart& p : models_[model].parts) names.push_back(p.pm() ? p.pm()->name() : p.source()->name());
    return names;
}

void SceneModels::release_detail(bool wait) {
    for (Model& m : models_) {
        if (!m.loader) continue;
        if (wait)
            m.loader->wait_until_done();
        else
            m.loader->release_detail();
    }
}

std::vector<std::unique_lock<std::mutex>> SceneModels::lock() const {
    std::vector<std::unique_lock<std::mutex>> locks;
    for (const Model& m : models_)
        if (m.streaming) locks.push_back(m.loader->lock());
    return locks;
}

bool SceneModels::poll_streams() {
    bool any = false;
    for (size_t i = 0; i < models_.size(); ++i) {
        Model& m = models_[i];
        if (!m.streaming) continue;
        check_stream(*m.loader, m.streaming, scene_.models[i].name);
        any = any || (m.streaming && !m.loader->paused());
    }
    return any;
}

void SceneModels::wait_until(std::chrono::steady_clock::time_point deadline) const {
    for (const Model& m : models_)
        if ((m.streaming || m.pending) && !m.loader->wait_idle_until(deadline)) return;
}

bool SceneModels::bind(size_t model, const ModelBinding& b, double now) {
    Model& m = models_[model];
    bool at_detail = true;
    const bool decoding = m.streaming && !m.loader->paused();
    for (size_t i = 0; i < m.parts.size(); ++i) {
        ModelPart& p = m.parts[i];
        render::ModelState* st = renderer_->state(p.id());
        st->style = b.style;
        st->visible = b.visible;
        st->selected = b.selected;
        st->cut = b.cut;
        st->transform = b.transform;
        if (b.hold_level)
            at_detail = at_detail && !p.progressive();
        else
            at_detail = p.head_for(*renderer_, b.lod_ratio, b.lod_automatic, b.glide, decoding, now) && at_detail;
        if (m.streaming) m.loader->want_splits(i, p.wanted_splits(b.lod_ratio));  // parts are the file's structures
        if (!m.streaming) p.hand_over_indices(*renderer_);
        p.apply_morph(*st);
    }
    return at_detail;
}

size_t SceneModels::triangles(size_t model) const {
    size_t n = 0;
    for (const ModelPart& p : models_[model].parts) n += p.triangles();
    return n;
}

std::optional<float> SceneModels::pick(size_t model, const glm::mat4& transform, const Ray& ray) {
    std::optional<float> best;
    for (ModelPart& p : models_[model].parts) {
        auto hit = p.pick(*renderer_, transform, ray);
        if (hit && (!best || *hit < *best)) best = hit;
    }
    return best;
}

void SceneModels::pick_many(size_t model, const glm::mat4& transform, std::span<const Ray> rays,
                            std::span<float> nearest) {
    for (ModelPart& p : models_[model].parts) p.pick_many(*renderer_, transform, rays, nearest);
}

}  // namespace body::kiosk
