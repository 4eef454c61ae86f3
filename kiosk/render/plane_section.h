#pragma once
// The section of a triangle mesh by a plane, as line segments (the cut
// plane's caps, kiosk/render/styles/cut_cap.cpp): every triangle with vertices
// on both sides of the plane gives the segment between its two crossing edges.
// A vertex is on the positive side when dot(n, p) + w > 0 and on the other
// side otherwise (on the plane included), so each edge is crossed or not the
// same way from both of its triangles, and the crossing point of an edge is
// computed from its endpoints in index order: the segments of a closed mesh
// join into closed loops exactly. The loops are the section's outlines;
// drawing the fan of a point with every segment, each pixel flipped per
// triangle covering it (even-odd), fills the section with its holes.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "shared/geometry.h"

namespace body::render {

// Appends to `segments` two points per crossed triangle (in the positions'
// space), for the triangles of `indices` (index_count / 3 of them; a triangle
// naming a vertex >= vertex_count is skipped) over `positions` (`stride`
// elements from one vertex to the next, x y z first). `plane` is (n, w) in
// the same space; `distance` is scratch (resized to vertex_count). Returns
// the number of segments appended. T: float, or uint16_t for quantized codes
// (pass the plane in code space).
template <typename T>
size_t plane_section(const T* positions, size_t stride, size_t vertex_count, const uint32_t* indices,
                     size_t index_count, const glm::vec4& plane, std::vector<Vec3f>& segments,
                     std::vector<float>& distance);

}  // namespace body::render
