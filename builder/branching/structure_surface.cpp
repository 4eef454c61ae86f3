// Building blocks shared by the bands, branches and caps of one structure.
#include "builder/branching/structure_surface.h"

#include "shared/mesh_intersect.h"

namespace body {

std::string where(const StructureSurface& surface, const Loop& loop) {
    const Contour& c = *loop.source;
    return surface.path + ": slice " + std::to_string(c.source_slice) + " contour " + std::to_string(c.source_contour);
}

std::vector<uint32_t> lifted_copy(StructureSurface& surface, std::span<const Vec2> xy, double at) {
    std::vector<uint32_t> ids;
    for (const Vec2& p : xy) {
        ids.push_back(uint32_t(surface.positions.size()));
        surface.positions.emplace_back(p.x, p.y, at);
    }
    return ids;
}

void prism(StructureSurface& surface, std::span<const uint32_t> lower, std::span<const uint32_t> upper) {
    const size_t n = lower.size();
    for (size_t i = 0; i < n; ++i) {
        const size_t j = (i + 1) % n;
        surface.triangles.insert(surface.triangles.end(), {lower[i], lower[j], upper[j]});
        surface.triangles.insert(surface.triangles.end(), {lower[i], upper[j], upper[i]});
    }
}

Status band(StructureSurface& surface, std::span<const uint32_t> lower, std::span<const uint32_t> upper,
            const Loop& blame) {
    std::vector<Vec3> a, b;
    for (uint32_t i : lower) a.push_back(surface.positions[i]);
    for (uint32_t i : upper) b.push_back(surface.positions[i]);
    std::vector<uint32_t> local;
    auto status = tile_band(a, b, surface.tiling, local);
    if (!status) return runtime_error(where(surface, blame) + ": tiling failed: " + status.error().message);
    for (uint32_t v : local) surface.triangles.push_back(v < a.size() ? lower[v] : upper[v - a.size()]);
    return ok_status();
}

size_t crossings_since(const StructureSurface& surface, size_t first_triangle_index) {
    return count_self_intersections(surface.positions,
                                    std::span<const uint32_t>(surface.triangles).subspan(first_triangle_index));
}

}  // namespace body
