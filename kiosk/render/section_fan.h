#pragma once
// The triangles that fill a plane section by even-odd count (the cut plane's
// caps, kiosk/render/styles/cut_cap.cpp): drawn into the stencil, each pixel
// flipped per triangle covering it, the pixels left odd are those inside the
// section's closed outlines (holes excluded), as with one fan of a single
// point with every segment, but with short triangles: a software rasterizer
// pays per screen tile each triangle crosses, and one apex makes every
// triangle reach across the section.
//
// Each segment fans to the centre of its cell in a grid over the section's
// box (`cells` per side); where two segments that share an end fan to
// different centres, the triangle (centre, end, centre) joins their spokes
// and the triangle (box centre, centre, centre) closes the edge between the
// centres. For closed outlines every added edge is met twice, so the count
// is the outline's; the ends are matched by their exact coordinates
// (plane_section.h gives both triangles of an edge the same point).
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "shared/geometry.h"

namespace body::render {

// Scratch kept between calls (no allocation once grown).
struct SectionFanScratch {
    struct End {
        uint32_t x, y, z;  // the point's bits
        bool operator==(const End&) const = default;
    };
    struct EndHash {
        size_t operator()(const End& e) const noexcept {
            return static_cast<size_t>((e.x * 0x9E3779B97F4A7C15ull) ^ (e.y * 0xC2B2AE3D27D4EB4Full) ^
                                       (e.z * 0x165667B19E3779F9ull));
        }
    };
    std::unordered_map<End, uint32_t, EndHash> ends;  // an end -> the cell its first segment fans to
};

// Appends to `fan` three points per triangle for the segments in `segments`
// (two points each, on the plane with unit normal `n`; `u`, `v` a unit basis
// of the plane, `lo`/`hi` the segments' box in (u, v)); `cells` >= 1 per
// side. Returns the number of triangles appended.
size_t section_fan(const std::vector<Vec3f>& segments, Vec3f n, Vec3f u, Vec3f v, glm::vec2 lo, glm::vec2 hi, int cells,
                   std::vector<Vec3f>& fan, SectionFanScratch& scratch);

// The grid side section_fan is given for `segment_count` segments: about 16
// segments per cell along the outline, 1 to 32 cells a side.
int section_fan_cells(size_t segment_count);

}  // namespace body::render
