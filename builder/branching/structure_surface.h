#pragma once
// The surface of one structure while the pipeline builds it: the mesh so far
// and, per slice, the structure's contours as loops with their mesh vertices.
// Tiling (bands), branching and caps append triangles; branching also appends
// vertices (chords, mid-slice rings) and marks which loops continue.
//
// Ids in `Loop::ids` and in the id loops below index `positions`; triangles are
// index triples into it, counter-clockwise seen from outside the solid.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "builder/correspondence/correspondence.h"
#include "builder/tiling/tiling.h"
#include "shared/error.h"
#include "shared/geometry.h"

namespace body {

// One contour of the structure on one slice.
struct Loop {
    const Contour* source = nullptr;
    std::vector<Vec2> xy;        // solid counter-clockwise, hole clockwise
    std::vector<uint32_t> ids;   // mesh vertices at the slice's z
    int parent = -1, depth = 0;  // nesting within the structure on this slice
    bool linked_up = false, linked_down = false;
    bool flat_caps = false;  // detached from a branch: a dome could reach into the neighbouring band
    int detached = 0;        // +1: the band below was refused (keep below clear), -1: the band above
    bool hole() const { return depth % 2 == 1; }
};

struct StructureSurface {
    // Set before building.
    std::string path;       // input file, named in error messages
    std::vector<double> z;  // slice heights
    // Per slice: a shape-based slice inserted at a branch (not for a topology
    // change); empty when none is. Ends beside them keep the input's gap.
    std::vector<bool> inserted_at_branch;
    TilingMethod tiling = TilingMethod::Multires;
    CorrespondenceMethod correspondence = CorrespondenceMethod::Overlap;
    // Built.
    std::vector<std::vector<Loop>> loops;  // per slice
    std::vector<Vec3> positions;
    std::vector<uint32_t> triangles;
};

// "PATH: slice S contour C" for the input contour of `loop`.
std::string where(const StructureSurface& surface, const Loop& loop);

// Appends `xy` at height `at` as new vertices; returns their ids.
std::vector<uint32_t> lifted_copy(StructureSurface& surface, std::span<const Vec2> xy, double at);

// Vertical prism between two congruent id loops of the same orientation.
void prism(StructureSurface& surface, std::span<const uint32_t> lower, std::span<const uint32_t> upper);

// Band between two id loops of the same orientation seen from +z (tiling/).
// A tiling failure is a runtime error naming `blame`'s contour.
Status band(StructureSurface& surface, std::span<const uint32_t> lower, std::span<const uint32_t> upper,
            const Loop& blame);

// Triangles appended since `first_triangle_index` that cross each other.
size_t crossings_since(const StructureSurface& surface, size_t first_triangle_index);

}  // namespace body
