#pragma once
// Geometry types shared by builder and kiosk: GLM vectors in double precision for
// the builder's exact work, float for the GPU side.
#include <glm/glm.hpp>

namespace body {

using Vec2 = glm::dvec2;
using Vec3 = glm::dvec3;
using Vec3f = glm::vec3;

struct Aabb {
    Vec3 min{1e300, 1e300, 1e300};
    Vec3 max{-1e300, -1e300, -1e300};
    void extend(const Vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    bool empty() const { return min.x > max.x; }
    Vec3 size() const { return empty() ? Vec3(0.0) : max - min; }
    double extent() const { return empty() ? 0.0 : glm::length(max - min); }
};

// A ray in world space (picking): origin and unit direction.
struct Ray {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit length
};

// Twice the signed area of a closed 2-D polygon (counter-clockwise positive).
inline double signed_area2(const Vec2* points, size_t count) {
    double a = 0.0;
    for (size_t i = 0, j = count - 1; i < count; j = i++) a += points[j].x * points[i].y - points[i].x * points[j].y;
    return a;
}

}  // namespace body
