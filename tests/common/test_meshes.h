#pragma once
// Meshes that tests and benchmarks generate instead of shipping files.
#include <cmath>
#include <cstdint>

#include "shared/mesh.h"

namespace body::test {

// A closed UV sphere: poles on ±z, `rings` latitude bands of `segments` quads
// (triangles at the poles), counter-clockwise seen from outside.
inline Mesh uv_sphere(int rings, int segments, Vec3 centre = Vec3(0.0), double radius = 1.0) {
    Mesh m;
    m.positions.push_back(centre + radius * Vec3(0, 0, 1));
    for (int r = 1; r < rings; ++r) {
        double t = M_PI * r / rings;
        for (int s = 0; s < segments; ++s) {
            double p = 2 * M_PI * s / segments;
            m.positions.push_back(centre +
                                  radius * Vec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)));
        }
    }
    m.positions.push_back(centre + radius * Vec3(0, 0, -1));
    auto ring = [&](int r, int s) { return uint32_t(1 + (r - 1) * segments + (s % segments)); };
    for (int s = 0; s < segments; ++s) m.indices.insert(m.indices.end(), {0, ring(1, s), ring(1, s + 1)});
    for (int r = 1; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s)
            m.indices.insert(m.indices.end(), {ring(r, s), ring(r + 1, s), ring(r + 1, s + 1), ring(r, s),
                                               ring(r + 1, s + 1), ring(r, s + 1)});
    uint32_t south = uint32_t(m.positions.size() - 1);
    for (int s = 0; s < segments; ++s)
        m.indices.insert(m.indices.end(), {south, ring(rings - 1, s + 1), ring(rings - 1, s)});
    return m;
}

}  // namespace body::test
