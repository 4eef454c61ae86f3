// Model files for the renderer (see model_source.h). References: Hoppe 1996,
// "Progressive meshes" (the .bpm runtime in shared/pm); meshoptimizer's
// meshopt_simplify for the OBJ preview LOD only.
#include "kiosk/render/model_source.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <filesystem>

#include "shared/obj_io.h"

namespace body::render {

ModelSource::ModelSource(std::string name, Vec3f color, std::vector<Vec3f> positions, std::vector<Vec3f> normals,
                         std::vector<uint32_t> indices)
    : name_(std::move(name)),
      color_(color),
      positions_(std::move(positions)),
      normals_(std::move(normals)),
      full_indices_(std::move(indices)) {
    positions_.shrink_to_fit();
    normals_.shrink_to_fit();
    full_indices_.shrink_to_fit();
}

ModelSource::ModelSource(std::unique_ptr<pm::ProgressiveMesh> pm) : pm_(std::move(pm)) {
    name_ = pm_->name();
    color_ = pm_->color();
    pm_->set_level(pm_->available_level());
}

size_t ModelSource::full_triangles() const { return pm_ ? pm_->max_triangle_count() : full_indices_.size() / 3; }
size_t ModelSource::triangles() const { return pm_ ? pm_->triangle_count() : current_indices().size() / 3; }

void ModelSource::set_lod(double ratio) {
    ratio = std::clamp(ratio, 0.0, 1.0);
    const auto target = static_cast<size_t>(static_cast<double>(full_triangles()) * ratio + 0.5);
    if (pm_) {
        pm_->set_level(pm_->level_for_triangles(std::max<size_t>(target, 1)));
        return;
    }
    const size_t old_size = current_indices().size();
    if (target >= full_indices_.size() / 3) {
        std::vector<uint32_t>().swap(
            indices_);  // the full level draws full_indices_: no second copy (`= {}` would keep the storage)
        simplified_ = false;
    } else {
        std::vector<uint32_t> out(full_indices_.size());
        size_t n =
            meshopt_simplify(out.data(), full_indices_.data(), full_indices_.size(), &positions_[0].x,
                             positions_.size(), sizeof(Vec3f), std::max<size_t>(target, 1) * 3, 1e-1f, 0, nullptr);
        out.resize(n);
        out.shrink_to_fit();
        indices_ = std::move(out);
        simplified_ = true;
    }
    const size_t size = current_indices().size();
    pending_.index_begin = 0;
    pending_.index_end = std::max(pending_.index_end, std::min(size, std::max(old_size, size)));
}

MeshData ModelSource::mesh() const {
    MeshData m;
    if (pm_) {
        m.positions = pm_->positions();
        if (pm_->has_normals()) m.normals = pm_->normals();
        m.indices = pm_->indices();
        m.vertex_count = pm_->vertex_count();
        m.index_count = 3 * pm_->triangle_count();
        return m;
    }
    m.positions = positions_;
    m.normals = normals_;
    m.indices = current_indices();
    return m;
}

Dirty ModelSource::take_dirty() {
    Dirty d;
    if (pm_) {
        if (first_) {
            d = {0, pm_->positions().size(), 0, pm_->indices().size()};
        } else {
            d = {pm_->dirty_vertices().begin, pm_->dirty_vertices().end, pm_->dirty_indices().begin,
                 pm_->dirty_indices().end};
        }
        pm_->clear_dirty();
    } else {
        d = first_ ? Dirty{0, positions_.size(), 0, current_indices().size()} : pending_;
        d.index_end = std::min(d.index_end, current_indices().size());
    }
    first_ = false;
    pending_ = Dirty{};
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

}  // namespace body::render
