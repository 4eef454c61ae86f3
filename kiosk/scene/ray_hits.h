#pragma once
// Several rays against one mesh in a single walk over its triangles
// (Möller-Trumbore, both sides): each triangle's corners are fetched and its
// edges formed once for all the rays. The pins' occlusion test casts one ray
// per pin through each model on its line of sight; walking the triangles once
// per model instead of once per pin saves the corner fetches (dequantised
// codes, or the element buffer read back from the GPU) and edge set-up.
//
// nearest[k] becomes the smaller of itself and the smallest t > 0 with
// rays[k].origin + t * rays[k].direction on a triangle (t in the units of the
// direction as given). `at(v)` gives vertex v's position.
#include <cmath>
#include <span>

#include "shared/geometry.h"

namespace body::kiosk {

template <class At>
void nearest_hits(std::span<const uint32_t> indices, const At& at, std::span<const Ray> rays,
                  std::span<float> nearest) {
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        const glm::vec3 a = at(indices[i]), b = at(indices[i + 1]), c = at(indices[i + 2]);
        const glm::vec3 e1 = b - a, e2 = c - a;
        for (size_t k = 0; k < rays.size(); ++k) {
            const glm::vec3 pv = glm::cross(rays[k].direction, e2);
            const float det = glm::dot(e1, pv);
            if (std::abs(det) < 1e-12f) continue;
            const float inv_det = 1.0f / det;
            const glm::vec3 tv = rays[k].origin - a;
            const float u = glm::dot(tv, pv) * inv_det;
            if (u < 0.0f || u > 1.0f) continue;
            const glm::vec3 qv = glm::cross(tv, e1);
            const float v = glm::dot(rays[k].direction, qv) * inv_det;
            if (v < 0.0f || u + v > 1.0f) continue;
            const float t = glm::dot(e2, qv) * inv_det;
            if (t > 0.0f && t < nearest[k]) nearest[k] = t;
        }
    }
}

}  // namespace body::kiosk
