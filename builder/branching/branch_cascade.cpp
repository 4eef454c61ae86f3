// The branching cascade: constructions tried in order, crossings checked.
#include "builder/branching/branch_cascade.h"

#include <optional>

#include "builder/branching/hull_ring.h"
#include "builder/branching/nested_region.h"
#include "builder/branching/partition_bands.h"
#include "builder/branching/union_ring.h"

namespace body {
namespace {

enum class Construction { Nested, Partition, UnionRing, PartitionDetached, HullRing };

// The cascade's order (see the header).
constexpr Construction kOrder[] = {Construction::Nested, Construction::Partition, Construction::UnionRing,
                                   Construction::PartitionDetached, Construction::HullRing};

Status construct(StructureSurface& surface, Construction method, size_t s, std::span<const uint32_t> gl,
                 std::span<const uint32_t> gu, bool hole) {
    switch (method) {
        case Construction::Nested: return connect_nested(surface, s, gl, gu, hole);
        case Construction::Partition: return connect_partition(surface, s, gl, gu, false);
        case Construction::PartitionDetached: return connect_partition(surface, s, gl, gu, true);
        case Construction::UnionRing: return connect_union_ring(surface, s, gl, gu, hole);
        case Construction::HullRing: break;
    }
    return connect_hull_ring(surface, s, gl, gu, hole);
}

}  // namespace

Status connect_branches(StructureSurface& surface, size_t s, std::span<const uint32_t> gl, std::span<const uint32_t> gu,
                        bool hole) {
    const bool one_side = gl.size() == 1 || gu.size() == 1;
    const size_t tri0 = surface.triangles.size(), pos0 = surface.positions.size();
    const std::vector<Loop> saved_lower = surface.loops[s], saved_upper = surface.loops[s + 1];
    auto roll_back = [&] {
        surface.triangles.resize(tri0);
        surface.positions.resize(pos0);
        surface.loops[s] = saved_lower;
        surface.loops[s + 1] = saved_upper;
    };
    std::optional<Construction> first_built;
    Status first_error = ok_status();
    for (Construction method : kOrder) {
        const bool needs_single = method != Construction::UnionRing && method != Construction::HullRing;
        if (!one_side && needs_single) continue;
        Status status = construct(surface, method, s, gl, gu, hole);
        if (status && crossings_since(surface, tri0) == 0) return status;
        if (status && !first_built) first_built = method;
        if (!status && first_error) first_error = status;
        roll_back();
    }
    if (!first_built)
        return first_error.ok() ? input_error(where(surface, surface.loops[s][gl[0]]) + ": branching failed")
                                : first_error;
    return construct(surface, *first_built, s, gl, gu, hole);
}

}  // namespace body
