// Bundles, .bpm and OBJ files -> ExportScene (contract in export_scene.h).
#include "builder/export/export_scene.h"

#include <cmath>
#include <filesystem>
#include <set>

#include "shared/obj_io.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "shared/scene/scene.h"

namespace body::exporter {
namespace {

namespace fs = std::filesystem;
using Mat4 = std::array<std::array<double, 4>, 4>;

Mat4 multiply(const Mat4& a, const Mat4& b) {
    Mat4 r{};
    for (size_t i = 0; i < 4; ++i)
        for (size_t j = 0; j < 4; ++j)
            for (size_t k = 0; k < 4; ++k) r[i][j] += a[i][k] * b[k][j];
    return r;
}

Mat4 rotation(int axis, double deg) {
    const double a = deg * 3.14159265358979323846 / 180.0, c = std::cos(a), s = std::sin(a);
    Mat4 r{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    const size_t u = size_t((axis + 1) % 3), v = size_t((axis + 2) % 3);
    r[u][u] = c, r[u][v] = -s, r[v][u] = s, r[v][v] = c;
    return r;
}

Mat4 placement(const scene::Transform& t) {
    Mat4 m{{{1, 0, 0, t.translate[0]}, {0, 1, 0, t.translate[1]}, {0, 0, 1, t.translate[2]}, {0, 0, 0, 1}}};
    m = multiply(m, rotation(2, t.rotate_deg[2]));
    m = multiply(m, rotation(1, t.rotate_deg[1]));
    m = multiply(m, rotation(0, t.rotate_deg[0]));
    const Mat4 s{{{t.scale, 0, 0, 0}, {0, t.scale, 0, 0}, {0, 0, t.scale, 0}, {0, 0, 0, 1}}};
    return multiply(m, s);
}

Result<std::vector<ExportModel>> models_of_file(const std::string& path, double lod) {
    std::vector<ExportModel> out;
    const std::string ext = fs::path(path).extension().string();
    if (ext == ".bpm") {
        auto pms = pm::read_bpm(path);
        if (!pms) return pms.error();
        for (auto& p : *pms) {
            p->set_level(p->level_for_triangles(size_t(std::floor(lod * double(p->max_triangle_count()) + 1e-9))));
            ExportModel m;
            m.name = p->name();
            m.mesh.name = p->name();
            m.mesh.color = Vec3(p->color());
            for (size_t v = 0; v < p->vertex_count(); ++v) m.mesh.positions.push_back(Vec3(p->position(v)));
            if (p->has_normals())
                for (size_t v = 0; v < p->vertex_count(); ++v) m.mesh.normals.push_back(Vec3(p->normal(v)));
            m.mesh.indices.assign(p->indices().begin(), p->indices().begin() + ptrdiff_t(p->triangle_count() * 3));
            m.quantization_bound = p->quantization_bound();
            out.push_back(std::move(m));
        }
        return out;
    }
    if (ext == ".obj") {
        auto meshes = read_obj(path);
        if (!meshes) return meshes.error();
        for (Mesh& mesh : *meshes) {
            ExportModel m;
            m.name = mesh.name.empty() ? fs::path(path).stem().string() : mesh.name;
            m.mesh = std::move(mesh);
            out.push_back(std::move(m));
        }
        return out;
    }
    return input_error(path + ": not an exportable model (expected a bundle, scene.json, .bpm or .obj)");
}

// Names made unique by a numeric suffix, in order.
void unique_names(std::vector<ExportModel>& models) {
    std::set<std::string> used;
    for (ExportModel& m : models) {
        std::string name = m.name.empty() ? "model" : m.name;
        for (int k = 2; used.count(name); ++k) name = m.name + "_" + std::to_string(k);
        used.insert(name);
        m.name = name;
    }
}

}  // namespace

Result<ExportScene> load_export_scene(const std::string& path, double lod) {
    if (!(lod > 0.0 && lod <= 1.0)) return input_error("export: --lod must be in (0, 1]");
    ExportScene out;
    std::error_code ec;
    std::string manifest = path;
    if (fs::is_directory(path, ec)) manifest = (fs::path(path) / "scene.json").string();
    if (manifest.ends_with(".json")) {
        auto s = scene::read_scene(manifest);
        if (!s) return s.error();
        for (const scene::Group& g : s->groups) out.groups.push_back(g.name);
        for (const scene::Model& sm : s->models) {
            auto models = models_of_file(sm.path, lod);
            if (!models) return models.error();
            for (ExportModel& m : *models) {
                m.name = models->size() == 1 ? sm.name : sm.name + "/" + m.name;
                m.group = sm.group;
                m.mesh.color = Vec3(sm.colour[0], sm.colour[1], sm.colour[2]);
                m.matrix = placement(sm.transform);
                out.models.push_back(std::move(m));
            }
        }
    } else {
        auto models = models_of_file(path, lod);
        if (!models) return models.error();
        out.models = std::move(*models);
    }
    unique_names(out.models);
    return out;
}

Vec3 place_point(const ExportModel& m, const Vec3& p) {
    Vec3 q;
    for (int r = 0; r < 3; ++r)
        q[r] = m.matrix[size_t(r)][0] * p.x + m.matrix[size_t(r)][1] * p.y + m.matrix[size_t(r)][2] * p.z +
               m.matrix[size_t(r)][3];
    return q;
}

Vec3 place_normal(const ExportModel& m, const Vec3& n) {
    // Rotation and uniform scale only: the linear part, renormalised.
    Vec3 q;
    for (int r = 0; r < 3; ++r)
        q[r] = m.matrix[size_t(r)][0] * n.x + m.matrix[size_t(r)][1] * n.y + m.matrix[size_t(r)][2] * n.z;
    const double len = glm::length(q);
    return len > 0.0 ? q / len : n;
}

}  // namespace body::exporter
