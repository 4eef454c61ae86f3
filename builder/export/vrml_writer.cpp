// ExportScene -> VRML97 (format notes in mesh_writers.h).
// Reference: ISO/IEC 14772-1:1997 (VRML97), Transform, Shape, IndexedFaceSet.
#include <cctype>
#include <cstdio>
#include <cstring>
#include <map>
#include <set>

#include "builder/export/mesh_writers.h"
#include "shared/atomic_file.h"
#include "shared/obj_io.h"

namespace body::exporter {

std::string vrml_identifier(const std::string& name) {
    // VRML97 Annex A: no control characters, space, quotes, #, comma, period, [ ] \ { }.
    std::string id;
    for (unsigned char c : name) {
        const bool bad = c <= 0x20 || c == 0x7f || std::strchr("\"'#,.[]\\{}+-", c) != nullptr;
        id.push_back(bad ? '_' : char(c));
    }
    if (id.empty() || std::isdigit(static_cast<unsigned char>(id[0]))) id.insert(id.begin(), '_');
    return id;
}

namespace {

void shape(std::string& out, const ExportModel& m, const std::string& id) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.4f %.4f %.4f", m.mesh.color.x, m.mesh.color.y, m.mesh.color.z);
    out += "DEF " + id + " Transform { children [ Shape {\n";
    out += "  appearance Appearance { material Material { diffuseColor " + std::string(buf) + " } }\n";
    out += "  geometry IndexedFaceSet { ccw TRUE solid TRUE\n    coord Coordinate { point [\n";
    for (const Vec3& p : m.mesh.positions) {
        const Vec3 q = place_point(m, p);
        std::snprintf(buf, sizeof buf, "      %.9g %.9g %.9g,\n", q.x, q.y, q.z);
        out += buf;
    }
    out += "    ] }\n    coordIndex [\n";
    for (size_t t = 0; t < m.mesh.triangle_count(); ++t) {
        std::snprintf(buf, sizeof buf, "      %u %u %u -1,\n", m.mesh.indices[t * 3], m.mesh.indices[t * 3 + 1],
                      m.mesh.indices[t * 3 + 2]);
        out += buf;
    }
    out += "    ]\n";
    if (m.mesh.normals.size() == m.mesh.positions.size()) {
        out += "    normalPerVertex TRUE normal Normal { vector [\n";
        for (const Vec3& n : m.mesh.normals) {
            const Vec3 q = place_normal(m, n);
            std::snprintf(buf, sizeof buf, "      %.6f %.6f %.6f,\n", q.x, q.y, q.z);
            out += buf;
        }
        out += "    ] }\n";
    }
    out += "  }\n} ] }\n";
}

}  // namespace

Status write_vrml(const std::string& path, const ExportScene& scene) {
    std::string out = "#VRML V2.0 utf8\n# bodygen export: one Transform per model, millimetres scaled to metres\n";
    out += "Transform { scale 0.001 0.001 0.001 children [\n";
    std::set<std::string> used;
    const auto unique = [&](const std::string& name) {
        std::string id = vrml_identifier(name);
        for (int k = 2; used.count(id); ++k) id = vrml_identifier(name) + "_" + std::to_string(k);
        used.insert(id);
        return id;
    };
    std::map<std::string, std::vector<const ExportModel*>> grouped;
    for (const ExportModel& m : scene.models) grouped[m.group].push_back(&m);
    for (const auto& [group, models] : grouped) {
        if (!group.empty()) out += "DEF " + unique(group) + " Transform { children [\n";
        for (const ExportModel* m : models) shape(out, *m, unique(m->name));
        if (!group.empty()) out += "] }\n";
    }
    out += "] }\n";
    return write_file_atomically(path,
                                 std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(out.data()), out.size()));
}

Status write_placed_obj(const std::string& path, const ExportScene& scene) {
    std::vector<Mesh> meshes;
    for (const ExportModel& m : scene.models) {
        Mesh mesh = m.mesh;
        mesh.name = m.name;
        for (Vec3& p : mesh.positions) p = place_point(m, p);
        for (Vec3& n : mesh.normals) n = place_normal(m, n);
        meshes.push_back(std::move(mesh));
    }
    ObjWriteOptions options;
    options.normals = true;
    return write_obj(path, meshes, options);
}

}  // namespace body::exporter
