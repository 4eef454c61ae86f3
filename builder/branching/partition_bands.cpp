// Partition branching on the structure's surface: pieces of the single loop
// tiled with their branches, optionally with interior branches detached.
#include "builder/branching/partition_bands.h"

#include <cmath>

#include "builder/branching/branching.h"
#include "builder/branching/chord_heights.h"
#include "builder/branching/nested_region.h"

namespace body {
namespace {

// Side branches inside the single loop `single` (slice `ss`) are detached; the
// largest branch (slice `bs`) never is. Returns the branches that stay linked.
std::vector<uint32_t> detach_interior(StructureSurface& surface, size_t ss, uint32_t single, size_t bs,
                                      std::span<const uint32_t> branches) {
    std::vector<Loop>& loops = surface.loops[bs];
    uint32_t main = branches[0];
    for (uint32_t b : branches)
        if (std::abs(signed_area2(loops[b].xy.data(), loops[b].xy.size())) >
            std::abs(signed_area2(loops[main].xy.data(), loops[main].xy.size())))
            main = b;
    std::vector<uint32_t> kept;
    for (uint32_t b : branches) {
        if (b != main && loops_nested(surface, ss, single, bs, std::span<const uint32_t>(&b, 1), false)) {
            Loop& loop = loops[b];
            (bs > ss ? loop.linked_down : loop.linked_up) = false;
            loop.flat_caps = true;
            loop.detached = bs > ss ? 1 : -1;
            continue;
        }
        kept.push_back(b);
    }
    return kept;
}

}  // namespace

Status split_into_bands(StructureSurface& surface, std::span<const uint32_t> single, const std::vector<Loop>& others,
                        std::span<const uint32_t> branch_ids, double chord_z, bool single_is_lower, const Loop& blame,
                        double blend_low) {
    std::vector<std::span<const Vec2>> branches;
    for (uint32_t k : branch_ids) branches.emplace_back(others[k].xy);
    const size_t first_chord = surface.positions.size();
    auto pieces = partition_contour(single, branches, chord_z, surface.positions);
    if (!pieces) return input_error(where(surface, blame) + ": branching: " + pieces.error().message);
    for (size_t b = 0; b < branch_ids.size(); ++b) {
        const auto& piece = (*pieces)[b];
        const auto& other = others[branch_ids[b]].ids;
        auto status = single_is_lower ? band(surface, piece, other, blame) : band(surface, other, piece, blame);
        if (!status) return status;
    }
    // The bands are tiled with the chords level (the tiling weighs 3D
    // lengths, and a chord near one slice pulls fans across the other loop),
    // then the chords move.
    if (blend_low >= 0) {
        std::vector<Vec2> single_xy;
        for (uint32_t id : single) single_xy.emplace_back(surface.positions[id]);
        blend_chord_heights(surface.positions, first_chord, single_xy, surface.positions[single[0]].z, branches,
                            surface.positions[others[branch_ids[0]].ids[0]].z, blend_low, 1 - kBlendLow);
    }
    return ok_status();
}

namespace {

// A partition's bands with blended chord heights (chord_heights.h) when they
// do not cross what was built, else with the chords at mid-slice.
Status split_blended(StructureSurface& surface, std::span<const uint32_t> single, const std::vector<Loop>& others,
                     std::span<const uint32_t> branch_ids, double chord_z, bool single_is_lower, const Loop& blame) {
    const size_t tri0 = surface.triangles.size(), pos0 = surface.positions.size();
    auto status = split_into_bands(surface, single, others, branch_ids, chord_z, single_is_lower, blame, kBlendLow);
    if (status && crossings_since(surface, tri0) == 0) return status;
    surface.triangles.resize(tri0);
    surface.positions.resize(pos0);
    return split_into_bands(surface, single, others, branch_ids, chord_z, single_is_lower, blame);
}

}  // namespace

Status connect_partition(StructureSurface& surface, size_t s, std::span<const uint32_t> gl,
                         std::span<const uint32_t> gu, bool detach) {
    const Loop& first_lower = surface.loops[s][gl[0]];
    const double zl = surface.z[s], zu = surface.z[s + 1];
    if (gl.size() == 1) {
        const std::vector<uint32_t> kept =
            detach ? detach_interior(surface, s, gl[0], s + 1, gu) : std::vector<uint32_t>(gu.begin(), gu.end());
        if (kept.size() == 1) return band(surface, first_lower.ids, surface.loops[s + 1][kept[0]].ids, first_lower);
        return split_blended(surface, first_lower.ids, surface.loops[s + 1], kept, 0.5 * (zl + zu), true, first_lower);
    }
    const std::vector<uint32_t> kept =
        detach ? detach_interior(surface, s + 1, gu[0], s, gl) : std::vector<uint32_t>(gl.begin(), gl.end());
    if (kept.size() == 1)
        return band(surface, surface.loops[s][kept[0]].ids, surface.loops[s + 1][gu[0]].ids, first_lower);
    return split_blended(surface, surface.loops[s + 1][gu[0]].ids, surface.loops[s], kept, 0.5 * (zl + zu), false,
                         first_lower);
}

}  // namespace body
