// Model files for the renderer (see model_source.h). References: Hoppe 1996,
// "Progressive meshes" (the .bpm runtime in shared/pm); meshoptimizer's
// meshopt_simplify for the OBJ preview LOD only.
#include "kiosk/scene/model_source.h"

#include <meshoptimizer.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <filesystem>
#include <span>

#include "shared/obj_io.h"
#include "shared/pm/bpm_reader.h"

namespace body::kiosk {

namespace {

// The triangles of `indices` in meshoptimizer's index codec; empty when they
// cannot be coded (the renderer reports such a mesh).
std::vector<uint8_t> encode_triangles(std::span<const uint32_t> indices) {
    if (indices.empty()) return {};
    const uint32_t top = *std::max_element(indices.begin(), indices.end());
    if (top == UINT32_MAX) return {};
    std::vector<uint8_t> code(meshopt_encodeIndexBufferBound(indices.size(), size_t{top} + 1));
    code.resize(meshopt_encodeIndexBuffer(code.data(), code.size(), indices.data(), indices.size()));
    code.shrink_to_fit();
    return code;
}

void decode_triangles(std::span<const uint8_t> code, size_t index_count, std::vector<uint32_t>& out) {
    out.resize(index_count);
    if (index_count > 0 && meshopt_decodeIndexBuffer(out.data(), index_count, code.data(), code.size()) != 0)
        out.clear();  // cannot happen for our own code; an empty level draws nothing
}

}  // namespace

ModelSource::ModelSource(std::string name, Vec3f color, std::vector<Vec3f> positions, std::vector<Vec3f> normals,
                         std::vector<uint32_t> indices)
    : name_(std::move(name)), color_(color), normals_(std::move(normals)), indices_(std::move(indices)) {
    normals_.shrink_to_fit();
    vertex_count_ = positions.size();
    indices_.resize(indices_.size() - indices_.size() % 3);  // whole triangles only
    indices_.shrink_to_fit();
    full_index_count_ = indices_.size();
    // Triangles in vertex-cache order and vertices in the order the triangles
    // first use them (meshoptimizer's Forsyth-like and fetch optimizers; unused
    // vertices keep their place at the end): the index codec then needs about
    // a third of the bytes (bench/RESULTS.md), and a draw's nearby triangles
    // share nearby vertices. The image is the same; vertex numbers change.
    if (!indices_.empty() && *std::max_element(indices_.begin(), indices_.end()) < vertex_count_) {
        meshopt_optimizeVertexCache(indices_.data(), indices_.data(), indices_.size(), vertex_count_);
        std::vector<uint32_t> remap(vertex_count_);
        size_t next = meshopt_optimizeVertexFetchRemap(remap.data(), indices_.data(), indices_.size(), vertex_count_);
        for (uint32_t& r : remap)
            if (r == ~0u) r = static_cast<uint32_t>(next++);
        meshopt_remapIndexBuffer(indices_.data(), indices_.data(), indices_.size(), remap.data());
        auto permute = [&](std::vector<Vec3f>& v) {
            std::vector<Vec3f> out(v.size());
            for (size_t i = 0; i < v.size(); ++i) out[remap[i]] = v[i];
            v = std::move(out);
        };
        permute(positions);
        if (normals_.size() == vertex_count_) permute(normals_);
    }
    box_min_ = box_max_ = positions.empty() ? Vec3f(0.0f) : positions.front();
    for (const Vec3f& p : positions) {
        box_min_ = glm::min(box_min_, p);
        box_max_ = glm::max(box_max_, p);
    }
    position_codes_.resize(positions.size() * 3);
    for (size_t v = 0; v < positions.size(); ++v)
        for (int k = 0; k < 3; ++k)
            position_codes_[v * 3 + static_cast<size_t>(k)] = pm::quantize16(positions[v][k], box_min_[k], box_max_[k]);
    std::vector<Vec3f>().swap(positions);
    full_code_ = encode_triangles(indices_);
}

ModelSource::ModelSource(std::unique_ptr<pm::ProgressiveMesh> pm) : pm_(std::move(pm)) {
    name_ = pm_->name();
    color_ = pm_->color();
    pm_->set_level(pm_->available_level());
}

size_t ModelSource::full_triangles() const { return pm_ ? pm_->max_triangle_count() : full_index_count_ / 3; }
size_t ModelSource::triangles() const { return pm_ ? pm_->triangle_count() : current_index_count() / 3; }

std::span<const uint32_t> ModelSource::current_indices() const {
    const Decoded want = simplified_ ? Decoded::Level : Decoded::Full;
    if (decoded_ != want) {
        decode_triangles(simplified_ ? level_code_ : full_code_, current_index_count(), indices_);
        decoded_ = want;
    }
    return indices_;
}

std::span<const Vec3f> ModelSource::positions() const {
    if (pm_ && pm_->vertex_data_released()) return {};  // the renderer's buffer has them
    if (!positions_decoded_ && pm_) {
        positions_.resize(pm_->max_vertex_count());
        pm_->positions(0, std::span<Vec3f>(positions_).first(pm_->available_level() + pm_->base_vertex_count()));
        positions_decoded_ = true;
    } else if (!positions_decoded_) {
        // Decoded in single precision as mesh.vert decodes them: the positions the GPU draws.
        const Vec3f scale = (box_max_ - box_min_) / 65535.0f;
        positions_.resize(vertex_count_);
        for (size_t v = 0; v < vertex_count_; ++v) {
            const uint16_t* c = &position_codes_[v * 3];
            positions_[v] = box_min_ + scale * Vec3f(c[0], c[1], c[2]);
        }
        positions_decoded_ = true;
    }
    return positions_;
}

render::MeshData mesh_data_of(pm::ProgressiveMesh& pm) {
    render::MeshData m;
    m.position_codes = pm.position_codes();
    m.has_position_box = true;
    m.position_box_min = pm.bounds_min();
    m.position_box_max = pm.bounds_max();
    m.normal_codes = pm.normal_codes();
    m.indices = pm.indices();
    m.vertex_count = pm.vertex_count();
    m.index_count = 3 * pm.triangle_count();
    // The arrays grow with the splits decoded; the renderer's limits are the file's.
    m.vertex_capacity = pm.max_vertex_count();
    m.index_capacity = 3 * pm.max_triangle_count();
    m.order_settled_levels = true;  // refinement order: a level that stays is drawn reordered
    pm::ProgressiveMesh* p = &pm;
    if (pm.vertex_data_released()) {
        // The renderer's buffers are the positions and normals: the parents'
        // moves are XORed into its codes, normals never change.
        m.position_patch = [p](std::span<uint16_t> window, size_t first) { p->patch_position_codes(window, first); };
        m.position_patch_begin = pm.pending_vertex_range().begin;
        m.position_patch_end = pm.pending_vertex_range().end;
    }
    if (pm.indices_packed()) {
        m.index_fill = [p](std::span<uint32_t> out) { p->fill_indices(out); };
        m.index_fill_count = 3 * pm.max_triangle_count();
    } else if (pm.indices_released()) {
        // The renderer's element buffer is the index array: the level's
        // patches are written into it.
        m.index_patch = [p](std::span<uint32_t> window, size_t first) { p->patch_indices(window, first); };
        m.index_patch_begin = pm.pending_index_range().begin;
        m.index_patch_end = pm.pending_index_range().end;
    }
    return m;
}

bool ModelSource::hands_over_indices() const {
    return pm_ && pm_->has_normals() && !pm_->indices_released() && pm_->available_level() == pm_->max_level();
}

render::MeshData ModelSource::upload_mesh() const { return upload_mesh_of(true); }

render::MeshData ModelSource::upload_mesh_of(bool hand_over) const {
    if (pm_) {
        pm::ProgressiveMesh* pm = pm_.get();
        // Complete: the array going up to add_model is the last use of ours.
        // Packed first, in place, so the new element buffer (which a driver
        // may clear at once) and our copy never hold two full arrays at the
        // upload's peak; the buffer is filled from it and it is freed.
        if (hand_over && hands_over_indices()) pm->pack_indices();
        return mesh_data_of(*pm);
    }
    render::MeshData m;
    m.position_codes = position_codes_;
    m.has_position_box = true;
    m.position_box_min = box_min_;
    m.position_box_max = box_max_;
    m.normals = normals_;
    m.indices = current_indices();
    return m;
}

void ModelSource::release_arrays() {
    size_t freed = (positions_.capacity() + pm_normals_.capacity()) * sizeof(Vec3f);
    std::vector<Vec3f>().swap(positions_);  // `= {}` would keep the storage
    std::vector<Vec3f>().swap(pm_normals_);
    positions_decoded_ = false;
    // A complete progressive mesh with normals hands its index array to the
    // renderer's buffer for good (12 bytes a triangle); without normals the
    // renderer computes them from the indices at every update, so it keeps them.
    if (hands_over_indices()) {
        const size_t bytes = pm_->indices().size() * sizeof(uint32_t);
        if (pm_->release_indices()) freed += bytes;
    }
    // Its positions and normals likewise, once the indices went (the renderer
    // has every vertex: add_model uploads them all).
    if (pm_ && pm_->indices_released() && !pm_->vertex_data_released()) {
        const size_t bytes = pm_->position_codes().size() * 2 + pm_->normal_codes().size();
        if (pm_->release_vertex_data()) freed += bytes;
    }
    // The current level's indices, unless they exist only plainly (no code).
    if (decoded_ != Decoded::None && !full_code_.empty() && (decoded_ == Decoded::Full || !level_code_.empty())) {
        freed += indices_.capacity() * sizeof(uint32_t);
        std::vector<uint32_t>().swap(indices_);
        decoded_ = Decoded::None;
    }
#ifdef __GLIBC__
    // glibc keeps big freed blocks on its heap once its mmap threshold grew
    // (after any earlier large free): hand them back.
    if (freed >= (1u << 20)) malloc_trim(0);
#else
    (void)freed;
#endif
}

void ModelSource::set_lod(double ratio) {
    ratio = std::clamp(ratio, 0.0, 1.0);
    const auto target = static_cast<size_t>(static_cast<double>(full_triangles()) * ratio + 0.5);
    if (pm_) {
        pm_->set_level(pm_->level_for_triangles(std::max<size_t>(target, 1)));
        positions_decoded_ = false;  // the level's floats are decoded again when asked for
        return;
    }
    const size_t old_size = current_index_count();
    std::vector<uint8_t>().swap(level_code_);
    if (target >= full_index_count_ / 3 || full_code_.empty()) {
        simplified_ = false;
        if (decoded_ == Decoded::Level) {
            std::vector<uint32_t>().swap(indices_);
            decoded_ = Decoded::None;  // the full level is decoded when asked for
        }
    } else {
        std::vector<uint32_t> full;  // the full level, decoded unless it is at hand
        if (decoded_ != Decoded::Full) decode_triangles(full_code_, full_index_count_, full);
        const std::span<const uint32_t> from = decoded_ == Decoded::Full ? std::span<const uint32_t>(indices_) : full;
        std::vector<uint32_t> out(from.size());
        const bool had_positions = positions_decoded_;
        const std::span<const Vec3f> positions = this->positions();
        size_t n = meshopt_simplify(out.data(), from.data(), from.size(), &positions[0].x, positions.size(),
                                    sizeof(Vec3f), std::max<size_t>(target, 1) * 3, 1e-1f, 0, nullptr);
        if (!had_positions) {  // decoded for the simplifier only
            std::vector<Vec3f>().swap(positions_);
            positions_decoded_ = false;
        }
        out.resize(n);
        out.shrink_to_fit();
        std::vector<uint32_t>().swap(full);
        // Coded now, with the simplifier's scratch, not when released (the
        // coder's worst-case buffer is 11 bytes a triangle).
        level_code_ = encode_triangles(out);
        indices_ = std::move(out);
        decoded_ = Decoded::Level;
        level_index_count_ = n;
        simplified_ = true;
    }
    const size_t size = current_index_count();
    pending_.index_begin = 0;
    pending_.index_end = std::max(pending_.index_end, std::min(size, std::max(old_size, size)));
}

render::MeshData ModelSource::mesh() const {
    // What an upload gets, plus floats for CPU readers; the arrays stay ours
    // (an upload of these does not hand the index array over).
    render::MeshData m = upload_mesh_of(false);
    m.positions = positions();
    if (pm_ && !pm_->vertex_data_released()) {
        if (pm_->has_normals() && pm_normals_.empty()) {
            pm_normals_.resize(pm_->max_vertex_count());
            for (size_t v = 0; v < pm_normals_.size(); ++v) pm_normals_[v] = pm_->normal(v);
        }
        m.normals = pm_normals_;
    }
    return m;
}

render::Dirty ModelSource::take_dirty() {
    render::Dirty d;
    if (pm_) {
        if (first_) {
            d = {0, pm_->max_vertex_count(), 0, 3 * pm_->max_triangle_count()};
        } else {
            d = {pm_->dirty_vertices().begin, pm_->dirty_vertices().end, pm_->dirty_indices().begin,
                 pm_->dirty_indices().end};
        }
        pm_->clear_dirty();
    } else {
        d = first_ ? render::Dirty{0, vertex_count_, 0, current_index_count()} : pending_;
        d.index_end = std::min(d.index_end, current_index_count());
    }
    first_ = false;
    pending_ = render::Dirty{};
    return d;
}

Result<std::vector<ModelSource>> load_model_file(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    std::vector<ModelSource> out;
    if (ext == ".bpm") {
        auto meshes = pm::read_bpm(path);
        if (!meshes) return meshes.error();
        for (auto& m : meshes.value()) {
            if (!m->base_ready() || m->base_triangle_count() == 0) continue;
            out.emplace_back(std::move(m));
        }
    } else if (ext == ".obj") {
        auto meshes = read_obj(path);
        if (!meshes) return meshes.error();
        for (Mesh& m : meshes.value()) {
            if (m.indices.empty()) continue;
            std::vector<Vec3f> p(m.positions.size()), n(m.normals.size());
            for (size_t i = 0; i < p.size(); ++i) p[i] = Vec3f(m.positions[i]);
            for (size_t i = 0; i < n.size(); ++i) n[i] = Vec3f(m.normals[i]);
            if (n.size() != p.size()) n.clear();
            out.emplace_back(m.name, Vec3f(m.color), std::move(p), std::move(n), std::move(m.indices));
        }
    } else {
        return input_error(path + ": unknown model type '" + ext + "' (expected .bpm or .obj)");
    }
    if (out.empty()) return input_error(path + ": no triangles in the file");
    return out;
}

}  // namespace body::kiosk
