// Nested-region branching: a height field between two sets of short walls.
#include "builder/branching/nested_region.h"

#include "builder/caps/boundary_distance.h"
#include "builder/caps/caps.h"
#include "builder/caps/dome_groups.h"
#include "builder/contours/validate.h"

namespace body {
namespace {

// The walls: a lifted copy of `xy` at `at`, joined to `ids` by a prism that
// runs upwards from the lower of the two.
std::vector<uint32_t> wall(StructureSurface& surface, std::span<const Vec2> xy, std::span<const uint32_t> ids,
                           double at, bool copy_above) {
    std::vector<uint32_t> copy = lifted_copy(surface, xy, at);
    if (copy_above)
        prism(surface, ids, copy);
    else
        prism(surface, copy, ids);
    return copy;
}

// The region's height field: one apex per group of its triangles
// (dome_groups.h), each group a fan around it. An apex at distance d_o from
// the outer ring and d_i from the inner loops sits at the fraction
// d_o / (d_o + d_i) of the way from the outer wall's top to the inner walls'
// foot: where the linear blend of the two slices' signed distances is zero
// (shape-based interpolation), so the region rises towards the loop it is
// nearer to instead of staying flat over triangles of one loop.
void lift_region(StructureSurface& surface, std::span<const std::span<const Vec2>> region,
                 std::span<const uint32_t> ids, double z_a, double z_b, std::span<const uint32_t> local, bool face_up) {
    std::vector<Vec2> flat;
    for (const auto& loop : region) flat.insert(flat.end(), loop.begin(), loop.end());
    std::vector<DomeGroup> groups;
    std::vector<uint32_t> cycles;
    dome_groups(flat, local, groups, cycles);
    if (region.size() < 2) return;  // callers always pass inner loops
    const BoundaryDistance to_outer(region.first(1)), to_inner(region.subspan(1));
    auto emit = [&](uint32_t a, uint32_t b, uint32_t c) {
        if (face_up)
            surface.triangles.insert(surface.triangles.end(), {a, b, c});
        else
            surface.triangles.insert(surface.triangles.end(), {a, c, b});
    };
    const auto lift = [&](const Vec2& p) {
        const double d_o = to_outer(p), d_i = to_inner(p);
        const double t = d_o + d_i > 0 ? d_o / (d_o + d_i) : 0.5;
        return Vec3(p, z_a + (z_b - z_a) * t);
    };
    lift_groups(groups, cycles, ids, lift, surface.positions, emit);
}

Status branch_region(StructureSurface& surface, size_t ss, uint32_t single, size_t bs,
                     std::span<const uint32_t> branches, bool hole) {
    const Loop& outer = surface.loops[ss][single];
    std::vector<const Loop*> inner;
    for (uint32_t b : branches) inner.push_back(&surface.loops[bs][b]);
    return nested_region(surface, outer.xy, outer.ids, surface.z[ss], inner, surface.z[bs], hole, outer);
}

}  // namespace

Status nested_region(StructureSurface& surface, std::span<const Vec2> outer_xy, std::span<const uint32_t> outer_ids,
                     double z_outer, std::span<const Loop* const> inner, double z_inner, bool hole, const Loop& blame,
                     double wall_outer, double wall_inner) {
    const double z_a = z_outer + (z_inner - z_outer) * wall_outer, z_b = z_inner - (z_inner - z_outer) * wall_inner;
    const bool outer_below = z_outer < z_inner;
    std::vector<std::span<const Vec2>> region{outer_xy};
    std::vector<uint32_t> ids = wall(surface, outer_xy, outer_ids, z_a, outer_below);
    for (const Loop* branch : inner) {
        std::vector<uint32_t> copy = wall(surface, branch->xy, branch->ids, z_b, !outer_below);
        region.emplace_back(branch->xy);
        ids.insert(ids.end(), copy.begin(), copy.end());
    }
    std::vector<uint32_t> local;
    auto status = triangulate_polygon_with_holes(region, local);
    if (!status) return input_error(where(surface, blame) + ": branching: " + status.error().message);
    // Triangles come out counter-clockwise from +z: right for the roof over a
    // solid that narrows upwards; the floor (outer above) and holes face the other way.
    const bool face_up = outer_below != hole;
    lift_region(surface, region, ids, z_a, z_b, local, face_up);
    return ok_status();
}

Status connect_through_ring(StructureSurface& surface, size_t s, std::span<const uint32_t> gl,
                            std::span<const uint32_t> gu, std::span<const Vec2> ring_xy, bool hole,
                            double wall_at_ring) {
    const Loop& first_lower = surface.loops[s][gl[0]];
    const double zl = surface.z[s], zu = surface.z[s + 1], zm = 0.5 * (zl + zu);
    const std::vector<uint32_t> mid = lifted_copy(surface, ring_xy, zm);
    std::vector<const Loop*> below, above;
    for (uint32_t k : gl) below.push_back(&surface.loops[s][k]);
    for (uint32_t k : gu) above.push_back(&surface.loops[s + 1][k]);
    auto status = nested_region(surface, ring_xy, mid, zm, below, zl, hole, first_lower, wall_at_ring);
    if (!status) return status;
    return nested_region(surface, ring_xy, mid, zm, above, zu, hole, first_lower, wall_at_ring);
}

bool loops_nested(const StructureSurface& surface, size_t ss, uint32_t single, size_t bs,
                  std::span<const uint32_t> branches, bool holes_matter) {
    const std::vector<Loop>& loops_s = surface.loops[ss];
    const std::vector<Loop>& loops_b = surface.loops[bs];
    const Loop& outer = loops_s[single];
    for (size_t k = 0; k < loops_s.size() && holes_matter; ++k)
        if (loops_s[k].parent == int(single)) return false;
    std::vector<std::span<const Vec2>> all{outer.xy};
    for (uint32_t b : branches) {
        for (size_t k = 0; k < loops_b.size() && holes_matter; ++k)
            if (loops_b[k].parent == int(b)) return false;
        for (const Vec2& p : loops_b[b].xy)
            if (!point_in_polygon(p, outer.xy)) return false;
        all.emplace_back(loops_b[b].xy);
    }
    return !find_crossing(all).found;
}

Status connect_nested(StructureSurface& surface, size_t s, std::span<const uint32_t> gl, std::span<const uint32_t> gu,
                      bool hole) {
    if (gl.size() == 1 && loops_nested(surface, s, gl[0], s + 1, gu))
        return branch_region(surface, s, gl[0], s + 1, gu, hole);
    if (gu.size() == 1 && loops_nested(surface, s + 1, gu[0], s, gl))
        return branch_region(surface, s + 1, gu[0], s, gl, hole);
    return input_error("not nested");
}

}  // namespace body
