// Open holes: a notched contour split between a solid contour and its holes.
#include "builder/branching/open_holes.h"

#include "builder/branching/partition_bands.h"
#include "builder/contours/validate.h"

namespace body {
namespace {

// Holes of `parent` (slice `ps`) that end towards slice `os` (no hole link
// continues them) and lie partly outside `other` there.
std::vector<uint32_t> open_holes(const StructureSurface& surface, size_t ps, uint32_t parent, size_t os, uint32_t other,
                                 std::span<const ContourLink> hole_links) {
    const std::vector<Loop>& here_loops = surface.loops[ps];
    const std::vector<Loop>& there_loops = surface.loops[os];
    std::vector<bool> linked(here_loops.size(), false);
    for (const ContourLink& l : hole_links) linked[os > ps ? l.lower : l.upper] = true;
    std::vector<uint32_t> open;
    for (uint32_t h = 0; h < here_loops.size(); ++h) {
        const Loop& loop = here_loops[h];
        if (linked[h] || !loop.hole() || loop.parent != int(parent)) continue;
        size_t outside = 0;
        for (const Vec2& p : loop.xy) outside += !point_in_polygon(p, there_loops[other].xy);
        if (4 * outside >= loop.xy.size()) open.push_back(h);
    }
    return open;
}

}  // namespace

Result<bool> connect_open_holes(StructureSurface& surface, size_t s, uint32_t lower, uint32_t upper,
                                std::span<const ContourLink> hole_links) {
    for (int side = 0; side < 2; ++side) {
        const size_t ps = side == 0 ? s : s + 1, os = side == 0 ? s + 1 : s;
        const uint32_t parent = side == 0 ? lower : upper, other = side == 0 ? upper : lower;
        std::vector<uint32_t> branches = open_holes(surface, ps, parent, os, other, hole_links);
        if (branches.empty()) continue;
        branches.insert(branches.begin(), parent);
        // First the chords where the two slices' distance fields blend to zero
        // (chord_heights.h: the notch's rim dips where its mouth is wide), then
        // only the parts that dip below mid-slice (near the notch's sides the
        // hole's band climbs to them), then level chords: the hole's band has
        // room to climb before it meets chords nearer the notched contour.
        const double tries[][2] = {{0.5, kBlendLow}, {0.5, 0.5}, {0.5, -1}, {0.7, -1}, {0.85, -1}, {0.95, -1}};
        for (const auto& [w, blend_low] : tries) {
            const size_t tri0 = surface.triangles.size(), pos0 = surface.positions.size();
            auto status = split_into_bands(surface, surface.loops[os][other].ids, surface.loops[ps], branches,
                                           w * surface.z[os] + (1 - w) * surface.z[ps], side == 1,
                                           surface.loops[ps][parent], blend_low);
            if (status && crossings_since(surface, tri0) == 0) {
                for (size_t b = 1; b < branches.size(); ++b) {
                    Loop& hole = surface.loops[ps][branches[b]];
                    (side == 0 ? hole.linked_up : hole.linked_down) = true;
                }
                return true;
            }
            surface.triangles.resize(tri0);
            surface.positions.resize(pos0);
        }
    }
    return false;
}

}  // namespace body
