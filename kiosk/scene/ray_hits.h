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
//
// Rays that share one origin (the pins' rays all leave the eye) take a
// cheaper test: the triangle's three edge planes through that origin are
// formed once per triangle, and a ray hits when its direction lies on the
// same side of all three (both windings), so each ray costs three dot
// products where Möller-Trumbore costs two cross products and four dots.
#include <algorithm>
#include <cmath>
#include <span>

#include "shared/geometry.h"

namespace body::kiosk {

template <class At>
void nearest_hits_from_one_origin(std::span<const uint32_t> indices, const At& at, std::span<const Ray> rays,
                                  std::span<float> nearest) {
    const glm::vec3 o = rays[0].origin;
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
        const glm::vec3 a = at(indices[i]) - o, b = at(indices[i + 1]) - o, c = at(indices[i + 2]) - o;
        const glm::vec3 ab = glm::cross(a, b), bc = glm::cross(b, c), ca = glm::cross(c, a);
        bool normal_ready = false;
        glm::vec3 n(0.0f);
        float a_n = 0.0f;
        for (size_t k = 0; k < rays.size(); ++k) {
            const glm::vec3& d = rays[k].direction;
            const float s1 = glm::dot(d, ab), s2 = glm::dot(d, bc), s3 = glm::dot(d, ca);
            if (!((s1 >= 0.0f && s2 >= 0.0f && s3 >= 0.0f) || (s1 <= 0.0f && s2 <= 0.0f && s3 <= 0.0f))) continue;
            if (!normal_ready) {  // the plane, for the few rays that pass the edges
                n = glm::cross(b - a, c - a);
                a_n = glm::dot(a, n);
                normal_ready = true;
            }
            const float dn = glm::dot(d, n);
            if (std::abs(dn) < 1e-12f) continue;  // along the plane
            const float t = a_n / dn;
            if (t > 0.0f && t < nearest[k]) nearest[k] = t;
        }
    }
}

template <class At>
void nearest_hits(std::span<const uint32_t> indices, const At& at, std::span<const Ray> rays,
                  std::span<float> nearest) {
    if (rays.empty()) return;
    const glm::vec3 o = rays[0].origin;
    if (std::all_of(rays.begin(), rays.end(), [&](const Ray& r) { return r.origin == o; }))
        return nearest_hits_from_one_origin(indices, at, rays, nearest);
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
