// The section of a mesh by a plane (contract in plane_section.h): signed
// distances once per vertex, then one pass over the triangles.
#include "kiosk/render/plane_section.h"

#include <utility>

namespace body::render {
namespace {

template <typename T>
Vec3f point(const T* positions, size_t stride, uint32_t v) {
    const T* p = positions + static_cast<size_t>(v) * stride;
    return Vec3f(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]));
}

template <typename T>
void signed_distances(const T* positions, size_t stride, size_t vertex_count, const glm::vec4& plane,
                      std::vector<float>& distance) {
    distance.resize(vertex_count);
    const Vec3f n(plane);
    for (size_t v = 0; v < vertex_count; ++v)
        distance[v] = glm::dot(n, point(positions, stride, static_cast<uint32_t>(v))) + plane.w;
}

// Where edge (a, b) crosses the plane, from its lower-numbered end, so both
// triangles of the edge get the same point.
template <typename T>
Vec3f crossing(const T* positions, size_t stride, const float* distance, uint32_t a, uint32_t b) {
    if (b < a) std::swap(a, b);
    const float t = distance[a] / (distance[a] - distance[b]);
    const Vec3f pa = point(positions, stride, a);
    return pa + (point(positions, stride, b) - pa) * t;
}

}  // namespace

template <typename T>
size_t plane_section(const T* positions, size_t stride, size_t vertex_count, const uint32_t* indices,
                     size_t index_count, const glm::vec4& plane, std::vector<Vec3f>& segments,
                     std::vector<float>& distance) {
    signed_distances(positions, stride, vertex_count, plane, distance);
    const float* d = distance.data();
    const size_t before = segments.size();
    for (size_t i = 0; i + 3 <= index_count; i += 3) {
        const uint32_t t[3] = {indices[i], indices[i + 1], indices[i + 2]};
        if (t[0] >= vertex_count || t[1] >= vertex_count || t[2] >= vertex_count) continue;
        const bool above[3] = {d[t[0]] > 0.0f, d[t[1]] > 0.0f, d[t[2]] > 0.0f};
        if (above[0] == above[1] && above[1] == above[2]) continue;
        // The vertex alone on its side is `lone`; the crossed edges are the two at it.
        const int lone = above[0] == above[1] ? 2 : above[0] == above[2] ? 1 : 0;
        const uint32_t a = t[lone], b = t[(lone + 1) % 3], c = t[(lone + 2) % 3];
        segments.push_back(crossing(positions, stride, d, a, b));
        segments.push_back(crossing(positions, stride, d, a, c));
    }
    return (segments.size() - before) / 2;
}

template size_t plane_section<float>(const float*, size_t, size_t, const uint32_t*, size_t, const glm::vec4&,
                                     std::vector<Vec3f>&, std::vector<float>&);
template size_t plane_section<uint16_t>(const uint16_t*, size_t, size_t, const uint32_t*, size_t, const glm::vec4&,
                                        std::vector<Vec3f>&, std::vector<float>&);

}  // namespace body::render
