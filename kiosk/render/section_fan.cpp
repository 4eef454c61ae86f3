// The section's even-odd triangles with one apex per grid cell (contract in
// section_fan.h).
#include "kiosk/render/section_fan.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace body::render {
namespace {

SectionFanScratch::End end_key(const Vec3f& p) {
    return {std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y), std::bit_cast<uint32_t>(p.z)};
}

struct Grid {
    Vec3f origin, step_u, step_v;  // cell (i, j)'s centre: origin + (i + 1/2) step_u + (j + 1/2) step_v
    glm::vec2 lo, size;
    int cells;
    uint32_t cell_of(const Vec3f& a, const Vec3f& b, Vec3f u, Vec3f v) const {
        const glm::vec2 at((glm::dot(a + b, u) * 0.5f - lo.x) / size.x, (glm::dot(a + b, v) * 0.5f - lo.y) / size.y);
        const int i = std::clamp(static_cast<int>(at.x * static_cast<float>(cells)), 0, cells - 1);
        const int j = std::clamp(static_cast<int>(at.y * static_cast<float>(cells)), 0, cells - 1);
        return static_cast<uint32_t>(j * cells + i);
    }
    Vec3f centre(uint32_t cell) const {
        const float i = static_cast<float>(cell % static_cast<uint32_t>(cells)) + 0.5f;
        const float j = static_cast<float>(cell / static_cast<uint32_t>(cells)) + 0.5f;
        return origin + step_u * i + step_v * j;
    }
};

}  // namespace

int section_fan_cells(size_t segment_count) {
    // An outline through g cells a side crosses about 4 g of them: 16 segments per cell.
    return std::clamp(static_cast<int>(static_cast<double>(segment_count) / 64.0), 1, 32);
}

size_t section_fan(const std::vector<Vec3f>& segments, Vec3f n, Vec3f u, Vec3f v, glm::vec2 lo, glm::vec2 hi, int cells,
                   std::vector<Vec3f>& fan, SectionFanScratch& scratch) {
    const size_t before = fan.size();
    if (segments.size() < 2) return 0;
    cells = std::max(cells, 1);
    const float along = glm::dot(segments.front(), n);  // every point is on the plane
    const glm::vec2 size = glm::max(hi - lo, glm::vec2(1e-30f));
    const Grid grid{n * along + u * lo.x + v * lo.y,
                    u * (size.x / static_cast<float>(cells)),
                    v * (size.y / static_cast<float>(cells)),
                    lo,
                    size,
                    cells};
    const Vec3f middle = n * along + u * (0.5f * (lo.x + hi.x)) + v * (0.5f * (lo.y + hi.y));
    scratch.ends.clear();
    for (size_t i = 0; i + 1 < segments.size(); i += 2) {
        const uint32_t cell = grid.cell_of(segments[i], segments[i + 1], u, v);
        const Vec3f apex = grid.centre(cell);
        fan.insert(fan.end(), {apex, segments[i], segments[i + 1]});
        for (size_t k = i; k < i + 2; ++k) {
            const Vec3f& end = segments[k];
            auto [at, inserted] = scratch.ends.try_emplace(end_key(end), cell);
            if (inserted || at->second == cell) continue;
            const Vec3f first = grid.centre(at->second);
            fan.insert(fan.end(), {first, end, apex, middle, first, apex});
        }
    }
    return (fan.size() - before) / 3;
}

}  // namespace body::render
