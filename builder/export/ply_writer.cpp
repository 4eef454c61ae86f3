// ExportScene -> binary little-endian PLY (format notes in mesh_writers.h).
#include <algorithm>
#include <cmath>

#include "builder/export/mesh_writers.h"
#include "shared/atomic_file.h"

namespace body::exporter {

Status write_ply(const std::string& path, const ExportScene& scene) {
    size_t vertices = 0, faces = 0;
    bool normals = !scene.models.empty();
    for (const ExportModel& m : scene.models) {
        vertices += m.mesh.vertex_count();
        faces += m.mesh.triangle_count();
        normals = normals && m.mesh.normals.size() == m.mesh.positions.size();
    }
    std::string header = "ply\nformat binary_little_endian 1.0\ncomment bodygen export, millimetres\n";
    size_t first = 0;
    for (const ExportModel& m : scene.models) {
        std::string name = m.name;
        std::replace_if(
            name.begin(), name.end(), [](char c) { return c == '\n' || c == '\r' || c == ' '; }, '_');
        header +=
            "comment model " + name + " " + std::to_string(first) + " " + std::to_string(m.mesh.vertex_count()) + "\n";
        first += m.mesh.vertex_count();
    }
    header += "element vertex " + std::to_string(vertices) + "\nproperty float x\nproperty float y\nproperty float z\n";
    if (normals) header += "property float nx\nproperty float ny\nproperty float nz\n";
    header += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
    header += "element face " + std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
    std::vector<uint8_t> out(header.begin(), header.end());
    const auto put_f = [&](double v) {
        const float f = float(v);
        const auto* b = reinterpret_cast<const uint8_t*>(&f);
        out.insert(out.end(), b, b + 4);
    };
    for (const ExportModel& m : scene.models) {
        const auto byte = [](double c) { return uint8_t(std::lround(std::clamp(c, 0.0, 1.0) * 255.0)); };
        for (size_t v = 0; v < m.mesh.vertex_count(); ++v) {
            const Vec3 p = place_point(m, m.mesh.positions[v]);
            put_f(p.x), put_f(p.y), put_f(p.z);
            if (normals) {
                const Vec3 n = place_normal(m, m.mesh.normals[v]);
                put_f(n.x), put_f(n.y), put_f(n.z);
            }
            out.insert(out.end(), {byte(m.mesh.color.x), byte(m.mesh.color.y), byte(m.mesh.color.z)});
        }
    }
    int32_t base = 0;
    for (const ExportModel& m : scene.models) {
        for (size_t t = 0; t < m.mesh.triangle_count(); ++t) {
            out.push_back(3);
            for (int k = 0; k < 3; ++k) {
                const int32_t i = base + int32_t(m.mesh.indices[t * 3 + size_t(k)]);
                const auto* b = reinterpret_cast<const uint8_t*>(&i);
                out.insert(out.end(), b, b + 4);
            }
        }
        base += int32_t(m.mesh.vertex_count());
    }
    return write_file_atomically(path, out);
}

}  // namespace body::exporter
