// One structure of a scene model on the GPU (contract in model_part.h).
#include "kiosk/scene/model_part.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "kiosk/scene/ray_hits.h"

namespace body::kiosk {

void Geomorph::start(double now, size_t from_triangles, size_t to_triangles) {
    started_ = true;
    start_ = now;
    from_ = from_triangles;
    to_ = to_triangles;
}

float Geomorph::factor(double now) const {
    if (!started_) return 1.0f;
    const float t = static_cast<float>(std::clamp((now - start_) / kSeconds, 0.0, 1.0));
    return t * t * (3.0f - 2.0f * t);
}

namespace {

void log_error(const Status& s) {
    if (!s) std::fprintf(stderr, "bodyview: %s\n", s.error().message.c_str());
}

// The level a streamed file is decoded to for `want` triangles (decoding on
// demand): the last batch boundary whose triangles stay within `want`. Once a
// batch is complete only its boundaries are drawn, so the next boundary would be
// decoded and never drawn (a small file's first batch is 64 splits: 16 times
// its 4-vertex base). Its triangles are estimated before it is decoded at the
// file's mean faces a split (exact for a closed surface: 2). Never below what
// is decoded; the whole file for its full detail.
size_t level_to_decode(const pm::ProgressiveMesh& m, size_t want) {
    const size_t have = m.available_level(), splits = m.max_level();
    if (want >= m.max_triangle_count()) return splits;
    const size_t triangles = m.triangles_at(have);
    if (have >= splits || triangles >= want) return have;
    const double per_split = double(m.max_triangle_count() - m.base_triangle_count()) / double(splits);
    const size_t reach = have + static_cast<size_t>(static_cast<double>(want - triangles) / std::max(per_split, 1.0));
    if (!m.batched()) return std::max(reach, have + 1);
    const auto levels = m.batch_levels();
    const auto it =
        std::upper_bound(levels.begin(), levels.end(), static_cast<uint32_t>(std::min<size_t>(reach, UINT32_MAX)));
    return it == levels.begin() ? have : std::max<size_t>(*(it - 1), have);
}

// The level `want` triangles would give once the whole file has arrived.
// Unknown while the file decodes (the batch arriving is not in its final
// order), or when the file is to be decoded further for `want`: then assume it
// needs more. A file paused on demand stops at level_to_decode, so a level
// below it is the whole file's.
size_t level_wanted(const pm::ProgressiveMesh& m, size_t want, bool decoding) {
    if (want >= m.max_triangle_count()) return m.max_level();
    if (m.available_level() < m.max_level() && (decoding || level_to_decode(m, want) > m.available_level()))
        return m.max_level();
    return m.level_for_triangles(want);
}

// Möller-Trumbore, both sides: the smallest t > 0 along (o, d) over `indices`.
template <class At>
void nearest_hit(std::span<const uint32_t> indices, const At& at, const glm::vec3& o, const glm::vec3& d, float& best) {
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        const glm::vec3 a = at(indices[i]), b = at(indices[i + 1]), c = at(indices[i + 2]);
        const glm::vec3 e1 = b - a, e2 = c - a, pv = glm::cross(d, e2);
        const float det = glm::dot(e1, pv);
        if (std::abs(det) < 1e-12f) continue;
        const float inv_det = 1.0f / det;
        const glm::vec3 tv = o - a;
        const float u = glm::dot(tv, pv) * inv_det;
        if (u < 0.0f || u > 1.0f) continue;
        const glm::vec3 qv = glm::cross(tv, e1);
        const float v = glm::dot(d, qv) * inv_det;
        if (v < 0.0f || u + v > 1.0f) continue;
        const float t = glm::dot(e2, qv) * inv_det;
        if (t > 0.0f && t < best) best = t;
    }
}

}  // namespace

ModelPart::ModelPart(std::unique_ptr<ModelSource> source)
    : source_(std::move(source)), base_triangles_(source_->full_triangles()) {}

ModelPart::ModelPart(pm::ProgressiveMesh& pm) : pm_(&pm), base_triangles_(pm.base_triangle_count()) {}

size_t ModelPart::full_triangles() const { return pm_ ? pm_->max_triangle_count() : source_->full_triangles(); }
size_t ModelPart::base_triangles() const { return base_triangles_; }
size_t ModelPart::triangles() const { return pm_ ? pm_->triangle_count() : source_->triangles(); }

render::MeshData ModelPart::mesh() const {
    if (!pm_) return source_->mesh();
    // Once the indices are handed over, with the hook that patches the element buffer.
    render::MeshData m = mesh_data_of(*pm_);
    m.morph_at_rest = true;  // at rest: nothing displaced
    return m;
}

Status ModelPart::upload(render::Renderer& renderer, const std::string& name) {
    // Plain meshes go up as their 16-bit position codes (no float copy).
    render::MeshData data = pm_ ? mesh() : source_->upload_mesh();
    data.prefix_only = pm_ != nullptr;  // the stream has not written the rest yet
    auto id = renderer.add_model(data, name);
    if (!id) return id.error();
    id_ = id.value();
    if (pm_) {
        // add_model uploaded the base level only; splits decoded along with
        // the base go up now (what arrives later is uploaded as it is used).
        const pm::DirtyRange v = pm_->dirty_vertices(), ix = pm_->dirty_indices();
        pm_->clear_dirty();
        if (v.end > v.begin || ix.end > ix.begin)
            return renderer.update_model(id_, mesh(), render::Dirty{v.begin, v.end, ix.begin, ix.end});
    } else {
        // The float arrays stay until the first head_for(): a preview LOD
        // simplifies the exact positions, not their 16-bit codes.
        (void)source_->take_dirty();
        arrays_kept_ = true;
    }
    return ok_status();
}

bool ModelPart::bounds(const render::Renderer& renderer, Vec3f& center, float& radius) const {
    if (!pm_) return renderer.bounds(id_, center, radius);
    center = (pm_->bounds_min() + pm_->bounds_max()) * 0.5f;
    radius = glm::length(pm_->bounds_max() - pm_->bounds_min()) * 0.5f;
    return true;
}

void ModelPart::upload_dirty(render::Renderer& renderer) {
    const pm::DirtyRange v = pm_->dirty_vertices(), i = pm_->dirty_indices();
    pm_->clear_dirty();
    if (v.end <= v.begin && i.end <= i.begin) return;
    log_error(renderer.update_model(id_, mesh(), render::Dirty{v.begin, v.end, i.begin, i.end}));
}

void ModelPart::hand_over_indices(render::Renderer& renderer) {
    // With normals: the renderer needs no indices to compute them. Positions
    // stay (geomorph sources and picking read them).
    if (!pm_ || pm_->indices_released() || !pm_->has_normals() || pm_->available_level() != pm_->max_level()) return;
    upload_dirty(renderer);
    pm_->release_indices();
}

void ModelPart::apply_morph(render::ModelState& state) const {
    state.morph_begin = gliding() ? morph_begin_ : SIZE_MAX;
    state.morph = gliding() ? morph_factor_ : 1.0f;
}

// Starts gliding between level `lo` and the current level (above it).
void ModelPart::start_morph(render::Renderer& renderer, size_t lo, double now) {
    upload_dirty(renderer);
    const size_t hi = pm_->level();
    const size_t begin = pm_->morph_sources(lo, morph_sources_);
    log_error(renderer.set_morph_sources(id_, begin, morph_sources_));
    morph_.start(now, pm_->triangles_at(collapsing_ ? hi : lo), pm_->triangles_at(collapsing_ ? lo : hi));
    morph_begin_ = begin;
    morph_end_ = begin + morph_sources_.size();
    morph_factor_ = collapsing_ ? 1.0f : 0.0f;
}

// Ends a glide where it is meant to end: the sources back to the positions.
void ModelPart::stop_morph(render::Renderer& renderer) {
    if (gliding()) {
        morph_sources_.resize(morph_end_ - morph_begin_);  // the positions, as floats
        pm_->positions(morph_begin_, morph_sources_);
        log_error(renderer.set_morph_sources(id_, morph_begin_, morph_sources_));
    }
    morph_begin_ = morph_end_ = 0;
    morph_factor_ = 1.0f;
    collapsing_ = false;
}

// The blend at `now`; a finished collapse drops the level.
void ModelPart::step_morph(render::Renderer& renderer, double now) {
    const float f = morph_.factor(now);
    morph_factor_ = collapsing_ ? 1.0f - f : f;
    if (f < 1.0f) return;
    const bool drop = collapsing_;
    stop_morph(renderer);
    if (!drop) return;
    pm_->set_level(pending_level_);
    upload_dirty(renderer);
}

// Glides towards `level`, uploading what changed.
void ModelPart::glide_to(render::Renderer& renderer, size_t level, double now) {
    if (collapsing_ && level == pending_level_) {
        step_morph(renderer, now);
        return;
    }
    if (gliding()) stop_morph(renderer);  // a new target: land the old glide at once
    const size_t current = pm_->level();
    if (level > current) {
        pm_->set_level(level);
        start_morph(renderer, current, now);
    } else if (level < current) {
        collapsing_ = true;
        pending_level_ = level;
        start_morph(renderer, level, now);
    }
    step_morph(renderer, now);
}

bool ModelPart::head_for_level(render::Renderer& renderer, double ratio, bool glide, bool streaming, double now) {
    // The level the ratio wants, as far as the stream has delivered it.
    const auto want = static_cast<size_t>(std::llround(static_cast<double>(full_triangles()) * ratio));
    // Once the file is complete the levels depend on `want` alone: a scene of
    // thousands of parts asks the same every frame, so the answer is kept.
    const bool complete = !streaming && pm_->available_level() >= pm_->max_level();
    if (!complete || want != cached_want_) {
        cached_level_ = pm_->level_for_triangles(std::max<size_t>(want, 1));
        cached_wanted_full_ = level_wanted(*pm_, want, streaming);
        cached_want_ = complete ? want : SIZE_MAX;
    }
    size_t level = cached_level_;
    const size_t wanted_full = cached_wanted_full_;
    // While detail streams in, refine in steps that at least quadruple the
    // triangles: each step costs an upload and a geomorph, and frames of a
    // half-way level compete with the decoding thread.
    if (streaming && level > pm_->level() && level < wanted_full &&
        pm_->triangles_at(level) < 4 * pm_->triangle_count())
        level = pm_->level();
    if (!glide) {
        if (gliding()) stop_morph(renderer);
        if (level != pm_->level()) {
            pm_->set_level(level);
            upload_dirty(renderer);
        }
    } else if (level != pm_->level() || gliding()) {
        glide_to(renderer, level, now);
    }
    return level >= wanted_full;
}

size_t ModelPart::wanted_splits(double ratio) const {
    if (!pm_) return 0;
    return level_to_decode(*pm_, static_cast<size_t>(std::llround(static_cast<double>(full_triangles()) * ratio)));
}

bool ModelPart::head_for(render::Renderer& renderer, double ratio, bool automatic, bool glide, bool streaming,
                         double now) {
    if (pm_) return head_for_level(renderer, ratio, glide, streaming, now);
    // An OBJ has no LOD hierarchy: a fixed ratio simplifies the whole mesh
    // (meshoptimizer preview); the automatic LOD leaves it at full detail.
    const double r = automatic ? 1.0 : ratio;
    if (r != source_ratio_) {
        source_ratio_ = r;
        source_->set_lod(r);
        log_error(renderer.update_model(id_, source_->upload_mesh(), source_->take_dirty()));
        arrays_kept_ = true;
    }
    if (arrays_kept_) source_->release_arrays();  // the renderer has its copy; picking decodes them again
    arrays_kept_ = false;
    return true;
}

std::optional<float> ModelPart::pick(const render::Renderer& renderer, const glm::mat4& transform, const Ray& ray) {
    const glm::mat4 inv = glm::inverse(transform);
    const glm::vec3 o = glm::vec3(inv * glm::vec4(ray.origin, 1.0f));
    const glm::vec3 d = glm::vec3(inv * glm::vec4(ray.direction, 0.0f));
    const render::MeshData m = mesh();
    // A pm keeps codes: dequantized per corner.
    const auto at = [&](uint32_t v) { return pm_ ? pm_->position(v) : m.positions[v]; };
    float best = 1e30f;
    if (pm_ && pm_->indices_released())
        renderer.read_indices(id_, m.index_count, [&](std::span<const uint32_t> ix) {
            nearest_hit(ix, at, o, d, best);  // the renderer's buffer holds the only copy
        });
    else
        nearest_hit(m.indices.first(std::min(m.index_count, m.indices.size())), at, o, d, best);
    if (source_) source_->release_arrays();  // what mesh() decoded
    if (best >= 1e30f) return std::nullopt;
    // t is in object units along d; convert to world distance.
    return best * glm::length(glm::vec3(transform * glm::vec4(d, 0.0f)));
}

void ModelPart::pick_many(const render::Renderer& renderer, const glm::mat4& transform, std::span<const Ray> rays,
                          std::span<float> nearest) {
    // An affine map keeps the ray parameter: t along the object-space ray is the world distance.
    const glm::mat4 inv = glm::inverse(transform);
    std::vector<Ray> local(rays.size());
    for (size_t k = 0; k < rays.size(); ++k) {
        local[k].origin = glm::vec3(inv * glm::vec4(rays[k].origin, 1.0f));
        local[k].direction = glm::vec3(inv * glm::vec4(rays[k].direction, 0.0f));
    }
    const render::MeshData m = mesh();
    const auto at = [&](uint32_t v) { return pm_ ? pm_->position(v) : m.positions[v]; };
    if (pm_ && pm_->indices_released())
        renderer.read_indices(id_, m.index_count, [&](std::span<const uint32_t> ix) {
            nearest_hits(ix, at, std::span<const Ray>(local), nearest);  // one read-back for every ray
        });
    else
        nearest_hits(m.indices.first(std::min(m.index_count, m.indices.size())), at, std::span<const Ray>(local),
                     nearest);
    if (source_) source_->release_arrays();
}

}  // namespace body::kiosk
