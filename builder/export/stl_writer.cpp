// ExportScene -> binary STL (format notes in mesh_writers.h).
#include <cstring>

#include "builder/export/mesh_writers.h"
#include "shared/atomic_file.h"

namespace body::exporter {

namespace {
void put(std::vector<uint8_t>& out, const void* p, size_t n) {
    out.insert(out.end(), static_cast<const uint8_t*>(p), static_cast<const uint8_t*>(p) + n);
}
void put_f(std::vector<uint8_t>& out, double v) {
    const float f = float(v);
    put(out, &f, 4);  // little-endian hosts (the project's targets)
}
}  // namespace

Status write_stl(const std::string& path, const ExportScene& scene) {
    std::vector<uint8_t> out(80, 0);
    const char header[] = "bodygen export: binary STL, millimetres, colours as VisCAM facet attributes";
    std::memcpy(out.data(), header, sizeof header - 1);
    uint32_t count = 0;
    for (const ExportModel& m : scene.models) count += uint32_t(m.mesh.triangle_count());
    put(out, &count, 4);
    for (const ExportModel& m : scene.models) {
        const auto c5 = [](double c) { return uint16_t(std::clamp(c, 0.0, 1.0) * 31.0 + 0.5); };
        const uint16_t attr =
            uint16_t(0x8000 | (c5(m.mesh.color.z) << 10) | (c5(m.mesh.color.y) << 5) | c5(m.mesh.color.x));
        for (size_t t = 0; t < m.mesh.triangle_count(); ++t) {
            Vec3 v[3];
            for (int k = 0; k < 3; ++k) v[k] = place_point(m, m.mesh.positions[m.mesh.indices[t * 3 + size_t(k)]]);
            Vec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
            const double len = glm::length(n);
            n = len > 0.0 ? n / len : Vec3(0.0);
            for (int k = 0; k < 3; ++k) put_f(out, n[k]);
            for (const Vec3& p : v)
                for (int k = 0; k < 3; ++k) put_f(out, p[k]);
            put(out, &attr, 2);
        }
    }
    return write_file_atomically(path, out);
}

}  // namespace body::exporter
