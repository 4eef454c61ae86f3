#pragma once
// Nested-region branching: when the branches on one slice lie inside the
// single loop on the other, the single loop rises as a vertical wall, the
// branches drop as vertical walls, and the planar region between them (outer
// minus branches) is triangulated and lifted between the walls, each group of
// its triangles a fan around an apex whose height follows the apex's distances
// to the outer and inner loops (shape-based interpolation): a height field
// over a planar subdivision, so it cannot fold or cross itself.
// The union-ring and hull constructions use the same region around a
// mid-slice ring.
#include <cstdint>
#include <span>
#include <vector>

#include "builder/branching/structure_surface.h"

namespace body {

// The region between an outer ring (`outer_xy` with vertices `outer_ids` at
// `z_outer`) and `inner` loops at `z_inner`: walls of `wall_outer` and
// `wall_inner` of the height difference, the lifted planar region between.
// `hole` flips the facing. Errors (input errors naming `blame`) when the
// region cannot be triangulated.
Status nested_region(StructureSurface& surface, std::span<const Vec2> outer_xy, std::span<const uint32_t> outer_ids,
                     double z_outer, std::span<const Loop* const> inner, double z_inner, bool hole, const Loop& blame,
                     double wall_outer = 1.0 / 3, double wall_inner = 1.0 / 3);

// A ring at mid-slice between slices s and s+1 (`ring_xy`, appended here as
// vertices) with the group's loops `gl` below and `gu` above, each side a
// nested region around it; `wall_at_ring` is the ring's wall fraction.
Status connect_through_ring(StructureSurface& surface, size_t s, std::span<const uint32_t> gl,
                            std::span<const uint32_t> gu, std::span<const Vec2> ring_xy, bool hole,
                            double wall_at_ring);

// Do `branches` on slice `bs` lie strictly inside loop `single` on slice `ss`
// (seen from above), with no other loop of the structure inside them or inside
// the single loop on its own slice? With `holes_matter` false only the
// containment is asked.
bool loops_nested(const StructureSurface& surface, size_t ss, uint32_t single, size_t bs,
                  std::span<const uint32_t> branches, bool holes_matter = true);

// The nested region between slices s and s+1 when one side of the group is a
// single loop holding the other side's loops; an input error ("not nested")
// otherwise, with nothing built.
Status connect_nested(StructureSurface& surface, size_t s, std::span<const uint32_t> gl, std::span<const uint32_t> gu,
                      bool hole);

}  // namespace body
