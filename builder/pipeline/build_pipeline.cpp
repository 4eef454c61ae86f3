// The contour-stack -> mesh pipeline, written as its stages in order:
//   1. validation and repair (contours/validate.h);
//   2. contours grouped into structures (correspondence/grouping.h);
//   3. per structure, on a StructureSurface (branching/structure_surface.h):
//      a. loops per slice, nested and oriented;
//      b. per slice pair: correspondence, then per link group a band
//         (tiling/) for 1:1, unless a hole opens into a notch
//         (branching/open_holes.h), else the branching cascade
//         (branching/branch_cascade.h);
//      c. caps where nothing continues, slabs for contours linked to nothing
//         (caps/);
//   then interpolation between slices and smoothing (fairing/) and the
//   mesh's statistics.
//
// References:
//   BodyGen/BodyView thesis, sections 2.3-2.6 (the stage structure).
//   H. Fuchs, Z. M. Kedem, S. P. Uselton, "Optimal surface reconstruction from
//     planar contours", CACM 20(10), 1977 (bands, via tiling/).
//   D. Meyers, S. Skinner, K. Sloan, "Surfaces from contours", ACM TOG 11(3),
//     1992 (the four sub-problems: correspondence, tiling, branching, fitting).
#include "builder/pipeline/build_pipeline.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <numeric>
#include <optional>
#include <thread>

#include "builder/branching/branch_cascade.h"
#include "builder/branching/open_holes.h"
#include "builder/branching/structure_surface.h"
#include "builder/caps/end_height.h"
#include "builder/contours/validate.h"
#include "builder/correspondence/grouping.h"
#include "builder/correspondence/link_overrides.h"
#include "builder/correspondence/material_regions.h"
#include "builder/correspondence/shape_slices.h"
#include "builder/fairing/slice_interpolation.h"
#include "shared/union_find.h"

namespace body {
namespace {

// ------------------------------------------- stage 3a: loops per slice

// The structure's contours on each slice, nested and oriented (solid
// counter-clockwise, hole clockwise), with their mesh vertices at the slice's z.
void make_loops(StructureSurface& surface, const ContourStack& stack,
                const std::vector<std::vector<uint32_t>>& members) {
    surface.loops.assign(stack.slices.size(), {});
    for (size_t s = 0; s < stack.slices.size(); ++s) {
        const Slice& slice = stack.slices[s];
        Nesting n = compute_nesting(slice, members[s]);
        for (size_t k = 0; k < members[s].size(); ++k) {
            Loop loop;
            loop.source = &slice.contours[members[s][k]];
            loop.xy = loop.source->points;
            loop.parent = n.parent[k];
            loop.depth = n.depth[k];
            const bool ccw = signed_area2(loop.xy.data(), loop.xy.size()) > 0;
            if (ccw == loop.hole()) std::reverse(loop.xy.begin(), loop.xy.end());
            loop.ids = lifted_copy(surface, loop.xy, slice.z);
            surface.loops[s].push_back(std::move(loop));
        }
    }
}

// ------------------------------ stage 3b: bands and branches per slab

// One link group between slices s and s+1: a band for 1:1 (unless a hole
// opens into a notch), the branching cascade otherwise; with the thesis's
// overlap branching every link of a branch is a band of its own.
Status connect_group(StructureSurface& surface, size_t s, const LinkGroup& group, bool hole, BranchingMethod branching,
                     std::span<const ContourLink> hole_links) {
    for (uint32_t k : group.lower) surface.loops[s][k].linked_up = true;
    for (uint32_t k : group.upper) surface.loops[s + 1][k].linked_down = true;
    const Loop& first_lower = surface.loops[s][group.lower[0]];
    if (branching == BranchingMethod::Overlap && group.lower.size() + group.upper.size() > 2) {
        for (const ContourLink& l : group.links) {
            auto status = band(surface, surface.loops[s][l.lower].ids, surface.loops[s + 1][l.upper].ids,
                               surface.loops[s][l.lower]);
            if (!status) return status;
        }
        return ok_status();
    }
    if (group.lower.size() == 1 && group.upper.size() == 1) {
        if (!hole) {
            auto built = connect_open_holes(surface, s, group.lower[0], group.upper[0], hole_links);
            if (!built || *built) return built ? ok_status() : Status(built.error());
        }
        return band(surface, first_lower.ids, surface.loops[s + 1][group.upper[0]].ids, first_lower);
    }
    return connect_branches(surface, s, group.lower, group.upper, hole);
}

// Correspondence between slices s and s+1 (material regions: solids with
// solids, holes with holes) with the stack's overrides, then one construction
// per link group.
Status connect(StructureSurface& surface, size_t s, BranchingMethod branching,
               std::span<const LinkOverride> overrides) {
    std::vector<PolygonSpan> xy[2];
    std::vector<int> parent[2];
    for (int side = 0; side < 2; ++side)
        for (const Loop& l : surface.loops[s + side]) xy[side].emplace_back(l.xy), parent[side].push_back(l.parent);
    const std::vector<ContourLink> all =
        correspond_nested({xy[0], parent[0]}, {xy[1], parent[1]}, surface.correspondence);
    std::vector<ContourLink> built[2];  // per kind, positions among that kind's loops
    std::vector<uint32_t> lo[2], up[2];
    for (int hole = 0; hole < 2; ++hole) {
        std::vector<uint32_t> at_lo(surface.loops[s].size()), at_up(surface.loops[s + 1].size());
        for (uint32_t k = 0; k < surface.loops[s].size(); ++k)
            if (surface.loops[s][k].hole() == bool(hole)) at_lo[k] = uint32_t(lo[hole].size()), lo[hole].push_back(k);
        for (uint32_t k = 0; k < surface.loops[s + 1].size(); ++k)
            if (surface.loops[s + 1][k].hole() == bool(hole))
                at_up[k] = uint32_t(up[hole].size()), up[hole].push_back(k);
        for (const ContourLink& l : all)
            if (surface.loops[s][l.lower].hole() == bool(hole)) built[hole].push_back({at_lo[l.lower], at_up[l.upper]});
        if (!overrides.empty() && !lo[hole].empty() && !up[hole].empty()) {
            std::vector<const Contour*> lower_src, upper_src;
            for (uint32_t k : lo[hole]) lower_src.push_back(surface.loops[s][k].source);
            for (uint32_t k : up[hole]) upper_src.push_back(surface.loops[s + 1][k].source);
            apply_link_overrides(overrides, lower_src, upper_src, built[hole]);
        }
    }
    // The hole links as loop indices: an open hole is one that none of them continues.
    std::vector<ContourLink> hole_links;
    for (const ContourLink& l : built[1]) hole_links.push_back({lo[1][l.lower], up[1][l.upper]});
    for (int hole = 0; hole < 2; ++hole) {
        for (LinkGroup& group : group_links(built[hole], lo[hole].size(), up[hole].size())) {
            // From positions among this kind of loop to loop indices on the slices.
            for (uint32_t& k : group.lower) k = lo[hole][k];
            for (uint32_t& k : group.upper) k = up[hole][k];
            for (ContourLink& l : group.links) l = {lo[hole][l.lower], up[hole][l.upper]};
            auto status = connect_group(surface, s, group, bool(hole), branching, hole_links);
            if (!status) return status;
        }
    }
    return ok_status();
}

// ------------------------------------------ stage 3c: caps and slabs

// Spacing to the neighbouring slices (for dome height and slabs).
double spacing(const StructureSurface& surface, size_t s, bool up) {
    const std::vector<double>& z = surface.z;
    const size_t S = z.size();
    if (up && s + 1 < S) return z[s + 1] - z[s];
    if (!up && s > 0) return z[s] - z[s - 1];
    if (s + 1 < S) return z[s + 1] - z[s];
    if (s > 0) return z[s] - z[s - 1];
    return 0.0;
}

// Loops linked to nothing on slice s become slabs a quarter spacing thick on
// each side: fills `top` and `bottom` with their rings (the loop's own ids on
// a side a detached branch does not grow to).
void make_slabs(StructureSurface& surface, size_t s, std::vector<std::vector<uint32_t>>& top,
                std::vector<std::vector<uint32_t>>& bottom) {
    auto& loops = surface.loops[s];
    const double zs = surface.z[s];
    double thick = std::min(spacing(surface, s, true), spacing(surface, s, false));
    if (!(thick > 0)) {
        Aabb box;
        for (const Loop& l : loops)
            for (const Vec2& p : l.xy) box.extend(Vec3(p, 0.0));
        thick = 0.1 * box.extent();
    }
    top.assign(loops.size(), {});
    bottom.assign(loops.size(), {});
    for (size_t k = 0; k < loops.size(); ++k) {
        const Loop& l = loops[k];
        if (l.linked_up || l.linked_down) continue;
        // A detached branch grows away from the band it was refused (one-sided slab).
        // A loop nested in a continuing one (a hole seen on one slice) stays
        // thin: the bands of its parent pass close by above and below.
        const bool inside_continuing =
            l.parent >= 0 && (loops[size_t(l.parent)].linked_up || loops[size_t(l.parent)].linked_down);
        const double half = inside_continuing ? 0.05 : 0.25;
        if (l.detached <= 0) {
            bottom[k] = lifted_copy(surface, l.xy, zs - (l.detached ? 2 * half : half) * thick);
            prism(surface, bottom[k], l.ids);
        } else {
            bottom[k] = l.ids;
        }
        if (l.detached >= 0) {
            top[k] = lifted_copy(surface, l.xy, zs + (l.detached ? 2 * half : half) * thick);
            prism(surface, l.ids, top[k]);
        } else {
            top[k] = l.ids;
        }
    }
}

// The gap an end on slice s may reach into facing `up` (or down): to the next
// input slice that way. Shape-based slices inserted in a gap where a structure
// branches do not shorten the ends of the input slice beside them (a hole
// seen on one slice only still goes as deep into the gap as without them).
double end_spacing(const StructureSurface& surface, size_t s, bool up) {
    const std::vector<bool>& inserted = surface.inserted_at_branch;
    if (inserted.empty() || inserted[s]) return spacing(surface, s, up);
    size_t t = s;
    if (up)
        while (t + 1 < surface.z.size() && inserted[t + 1]) ++t;
    else
        while (t > 0 && inserted[t - 1]) --t;
    if (t == s) return spacing(surface, s, up);
    const double next =
        up ? (t + 1 < surface.z.size() ? surface.z[t + 1] : surface.z[t]) : (t > 0 ? surface.z[t - 1] : surface.z[t]);
    return std::abs(next - surface.z[s]);
}

// Caps on slice s facing `up` (or down): over the loops that end there
// (`slab` false: own rings at the slice's z) or over the slab rings.
Status cap_slice(StructureSurface& surface, size_t s, bool up, bool slab, CapStyle caps, bool lift_chords,
                 const std::vector<std::vector<uint32_t>>& top, const std::vector<std::vector<uint32_t>>& bottom,
                 const RungPartners& partners) {
    const auto& loops = surface.loops[s];
    std::vector<bool> in(loops.size(), false);
    for (size_t k = 0; k < loops.size(); ++k) {
        const Loop& l = loops[k];
        const bool isolated = !l.linked_up && !l.linked_down;
        in[k] = slab ? isolated : (!isolated && !(up ? l.linked_up : l.linked_down));
    }
    // A cap region is a loop with the loops inside it that end with it; a loop
    // ending inside such a region's inner loop (an island in an ending hole)
    // starts a region of its own. Parents come before children by depth.
    std::vector<size_t> by_depth(loops.size());
    std::iota(by_depth.begin(), by_depth.end(), size_t(0));
    std::stable_sort(by_depth.begin(), by_depth.end(),
                     [&](size_t a, size_t b) { return loops[a].depth < loops[b].depth; });
    std::vector<bool> root(loops.size(), false);
    for (size_t k : by_depth) root[k] = in[k] && !(loops[k].parent >= 0 && root[size_t(loops[k].parent)]);
    const auto& ring = up ? top : bottom;
    for (size_t k = 0; k < loops.size(); ++k) {
        if (!root[k]) continue;
        std::vector<std::span<const Vec2>> region{loops[k].xy};
        std::vector<std::span<const uint32_t>> ids{slab ? ring[k] : loops[k].ids};
        const double at = surface.positions[ids[0][0]].z;
        // An end's dome: as high as the bands' slope says it goes on, at most
        // 0.45 of the gap (end_height.h; under half, so that two ends facing
        // each other across one gap stay apart); a slab's: most of the slab's half.
        EndHeight end{0.8 * std::abs(at - surface.z[s]), false};
        if (!slab)
            end = end_height(loops[k].xy, loops[k].ids, surface.positions, partners, up,
                             0.45 * end_spacing(surface, s, up));
        const double dome = end.height;
        for (size_t c = 0; c < loops.size(); ++c)
            if (in[c] && loops[c].parent == int(k)) {
                region.emplace_back(loops[c].xy);
                ids.emplace_back(slab ? ring[c] : loops[c].ids);
            }
        // A region whose outer loop is a hole faces the other way.
        const bool face_up = up != loops[k].hole();
        const CapStyle style = loops[k].flat_caps && caps == CapStyle::Dome ? CapStyle::Flat : caps;
        // A hole's void goes on past the slice where its band ends: its dome
        // bulges away from the faces, into the solid (a dome towards the faces
        // would stretch across the void the hole's band bounds).
        const double height = loops[k].hole() && !slab ? -dome : dome;
        auto status = build_cap(region, ids, at, face_up, style, height, surface.positions, surface.triangles,
                                end.closing, lift_chords);
        if (!status) return input_error(where(surface, loops[k]) + ": " + status.error().message);
    }
    return ok_status();
}

// Caps where nothing continues, slabs for contours linked to nothing. Domes
// lift their chords (caps.h) where the bands will be interpolated: a curved
// side ending in a dome that is flat along its chords leaves the cap the
// farthest part of the mesh; the linear build keeps its flat chords (its
// tests and LOD levels were measured on them).
Status close_ends(StructureSurface& surface, CapStyle caps, bool lift_chords) {
    std::vector<std::vector<uint32_t>> top, bottom;
    RungPartners partners;  // of the bands built so far: the caps' slopes
    rung_partners(surface.positions, surface.triangles, partners);
    for (size_t s = 0; s < surface.loops.size(); ++s) {
        if (surface.loops[s].empty()) continue;
        make_slabs(surface, s, top, bottom);
        for (int up = 0; up < 2; ++up)
            for (int slab = 0; slab < 2; ++slab) {
                auto status = cap_slice(surface, s, bool(up), bool(slab), caps, lift_chords, top, bottom, partners);
                if (!status) return status;
            }
    }
    return ok_status();
}

// --------------------------------- stage 3a: shape-based slices between

// Halvings of a gap at most: each inserted slice can need one more between it
// and a neighbour.
constexpr int kShapeSliceDepth = 2;
constexpr double kDenseGapVoxels = 1.5;

// One shape-based slice to insert.
struct InsertedSlice {
    double z = 0.0;
    std::vector<Contour> contours;
    bool at_branch = false;  // for a branch or a piece of its own (shape_slices.h)
};

// Shape-based slices between `lower` and `upper` (at zl, zu), in z order,
// appended to `out`; at branches too when `at_branches` (shape_slices.h).
void shape_slices_between(std::span<const std::span<const Vec2>> lower, std::span<const std::span<const Vec2>> upper,
                          double zl, double zu, int depth, bool at_branches, std::vector<InsertedSlice>& out) {
    if (depth == 0) return;
    ShapeSlice shaped = shape_slice_between(lower, upper, at_branches);
    std::vector<std::vector<Vec2>>& rings = shaped.rings;
    if (rings.empty()) return;
    const double zm = zl + shaped.t * (zu - zl);
    std::vector<std::span<const Vec2>> mid(rings.begin(), rings.end());
    std::vector<InsertedSlice> below, above;
    // A gap split for a topology change is left to the hole constructions:
    // only gaps split at a branch are split again at branches.
    const bool again = at_branches && shaped.at_branch;
    shape_slices_between(lower, mid, zl, zm, depth - 1, again, below);
    shape_slices_between(mid, upper, zm, zu, depth - 1, again, above);
    std::vector<Contour> contours(rings.size());
    for (size_t k = 0; k < rings.size(); ++k) contours[k].points = std::move(rings[k]);
    for (auto& b : below) out.push_back(std::move(b));
    out.push_back({zm, std::move(contours), shaped.at_branch});
    for (auto& a : above) out.push_back(std::move(a));
}

// The structure's own stack with shape-based slices inserted where a slice
// pair's topology changes between them, and with `at_branches` (the
// interpolated build) where it branches or a piece of its own lies between
// them; false (nothing filled) when none is. The linear build keeps its
// bands and branches: its tests and LOD levels were measured on them, and the
// traced sections' raster steps (a few thousandths of the extent) would show
// in an unsmoothed mesh.
// A label volume's gaps of at most kDenseGapVoxels voxels (ContourStack::voxel)
// get no branch sections: between two neighbouring voxel planes the map says
// nothing finer than the voxel step, so the sections would only add triangles
// and build time (bench/RESULTS.md); sparser label stacks (every 2nd voxel
// and up) and traced stacks keep them.
// Stacks with link overrides keep their slices (the overrides name adjacent
// slices of the file). An inserted contour names the lower slice's first
// member as its source (for messages). `inserted` and `at_branch` flag the
// local stack's slices: inserted, and inserted for a branch.
bool with_shape_slices(const ContourStack& stack, const std::vector<std::vector<uint32_t>>& members,
                       ContourStack& local, std::vector<std::vector<uint32_t>>& local_members,
                       std::vector<bool>& inserted, std::vector<bool>& at_branch, bool at_branches) {
    if (!stack.links.empty()) return false;
    std::vector<std::vector<InsertedSlice>> between(stack.slices.size());
    bool any = false;
    std::vector<std::span<const Vec2>> polys[2];
    for (size_t s = 0; s + 1 < stack.slices.size(); ++s) {
        if (members[s].empty() || members[s + 1].empty()) continue;
        for (int side = 0; side < 2; ++side) {
            polys[side].clear();
            for (uint32_t k : members[s + side]) polys[side].emplace_back(stack.slices[s + side].contours[k].points);
        }
        const double gap = stack.slices[s + 1].z - stack.slices[s].z;
        const bool dense = stack.voxel && gap <= kDenseGapVoxels * *stack.voxel;
        shape_slices_between(polys[0], polys[1], stack.slices[s].z, stack.slices[s + 1].z, kShapeSliceDepth,
                             at_branches && !dense, between[s]);
        any = any || !between[s].empty();
    }
    if (!any) return false;
    local.slices.clear();
    local_members.clear();
    inserted.clear();
    at_branch.clear();
    auto add = [&](Slice slice, bool is_inserted, bool for_branch) {
        local_members.emplace_back(slice.contours.size());
        std::iota(local_members.back().begin(), local_members.back().end(), uint32_t(0));
        local.slices.push_back(std::move(slice));
        inserted.push_back(is_inserted);
        at_branch.push_back(for_branch);
    };
    for (size_t s = 0; s < stack.slices.size(); ++s) {
        Slice own{stack.slices[s].z, {}, stack.slices[s].source_index};
        for (uint32_t k : members[s]) own.contours.push_back(stack.slices[s].contours[k]);
        add(std::move(own), false, false);
        for (InsertedSlice& in : between[s]) {
            const Contour& src = stack.slices[s].contours[members[s][0]];
            for (Contour& c : in.contours) {
                c.structure = src.structure;
                c.source_slice = src.source_slice;
                c.source_contour = src.source_contour;
            }
            add(Slice{in.z, std::move(in.contours), stack.slices[s].source_index}, true, in.at_branch);
        }
    }
    return true;
}

// ------------------------------------------------ stage 3: one structure

// Mesh pieces (triangles connected through shared vertices) that meet no
// input contour removed, with the vertices no triangle uses; the rest keep
// their order. Such pieces are made of inserted slices' contours alone (a
// hole of the mean section that matches no hole of either slice, closed by
// caps): a cavity or a fragment that no input slice shows.
void drop_inserted_pieces(StructureSurface& surface, const std::vector<bool>& inserted) {
    std::vector<Vec3>& positions = surface.positions;
    std::vector<uint32_t>& triangles = surface.triangles;
    UnionFind sets(positions.size());
    for (size_t t = 0; t + 2 < triangles.size(); t += 3)
        for (int k = 1; k < 3; ++k) sets.unite(triangles[t + k], triangles[t]);
    std::vector<uint8_t> real(positions.size(), 0);  // per root: the piece meets an input contour
    for (size_t s = 0; s < surface.loops.size(); ++s)
        if (!inserted[s])
            for (const Loop& l : surface.loops[s])
                for (uint32_t v : l.ids) real[sets.find(v)] = 1;
    size_t kept = 0;
    for (size_t t = 0; t + 2 < triangles.size(); t += 3)
        if (real[sets.find(triangles[t])])
            for (int k = 0; k < 3; ++k) triangles[kept++] = triangles[t + k];
    if (kept == triangles.size()) return;
    triangles.resize(kept);
    std::vector<uint32_t> to(positions.size(), 0);
    for (uint32_t v : triangles) to[v] = 1;
    uint32_t n = 0;
    for (size_t v = 0; v < positions.size(); ++v)
        if (to[v]) positions[n] = positions[v], to[v] = n++;
    positions.resize(n);
    for (uint32_t& v : triangles) v = to[v];
}

// The surface of one structure: loops, then per slab bands and branches, then
// caps. `advance` is called once per slice (progress).
Status build_surface(StructureSurface& surface, const ContourStack& stack, const BuildOptions& options,
                     const std::vector<std::vector<uint32_t>>& members, const std::function<void()>& advance) {
    make_loops(surface, stack, members);
    for (size_t s = 0; s + 1 < surface.loops.size(); ++s) {
        if (!surface.loops[s].empty() || !surface.loops[s + 1].empty()) {
            auto status = connect(surface, s, options.branching, stack.links);
            if (!status) return status;
        }
        advance();
    }
    advance();
    return close_ends(surface, options.caps, options.interpolate > 0);
}

// One structure of a validated stack: its mesh and statistics.
Result<StructureMesh> build_structure(const ContourStack& stack, const StructureGroups& grouping, size_t i,
                                      const BuildOptions& options, const std::string& source_path,
                                      const std::function<void()>& advance, unsigned inner_threads) {
    const auto& members = grouping.members[i];
    size_t contours = 0;
    for (const auto& v : members) contours += v.size();
    const auto start = std::chrono::steady_clock::now();
    // Inserted slices do not count for progress: one step per stack slice.
    ContourStack local;
    std::vector<std::vector<uint32_t>> local_members;
    std::vector<bool> inserted, at_branch;
    const bool shaped =
        with_shape_slices(stack, members, local, local_members, inserted, at_branch, options.interpolate > 0);
    size_t step = 0;
    const std::function<void()> own_advance = [&] {
        if (!shaped || step >= inserted.size() || !inserted[step]) advance();
        ++step;
    };
    const ContourStack& used = shaped ? local : stack;
    StructureSurface surface;
    surface.path = source_path;
    for (const Slice& slice : used.slices) surface.z.push_back(slice.z);
    if (shaped) surface.inserted_at_branch = at_branch;
    surface.tiling = options.tiling;
    surface.correspondence = options.correspondence;
    auto status = build_surface(surface, used, options, shaped ? local_members : members, own_advance);
    if (!status) return status.error();
    if (shaped) drop_inserted_pieces(surface, inserted);
    StructureMesh sm;
    sm.id = grouping.infos[i].id;
    sm.contours = contours;
    sm.mesh.name = grouping.infos[i].name;
    sm.mesh.color = grouping.infos[i].color;
    sm.mesh.positions = std::move(surface.positions);
    sm.mesh.indices = std::move(surface.triangles);
    sm.interpolation_straightened =
        interpolate_between_slices(sm.mesh.positions, sm.mesh.indices, surface.z, options.interpolate,
                                   options.ring_tolerance, options.ring_voxel * stack.voxel.value_or(0.0),
                                   inner_threads)
            .straightened;
    sm.fairing_restored = taubin_smooth(sm.mesh.positions, sm.mesh.indices, options.fairing);
    const MeshTopology topo = analyze_topology(sm.mesh.positions, sm.mesh.indices);
    sm.triangles = sm.mesh.triangle_count();
    sm.volume = mesh_volume(sm.mesh.positions, sm.mesh.indices);
    sm.area = mesh_area(sm.mesh.positions, sm.mesh.indices);
    sm.closed_manifold = topo.closed_manifold();
    sm.genus = topo.genus();
    sm.components = topo.components;
    sm.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return sm;
}

}  // namespace

Result<std::vector<StructureMesh>> build_structures(const ContourStack& input, const BuildOptions& options,
                                                    const std::string& source_path) {
    // Stage 1: validation and repair, without the contours the links exclude.
    ContourStack stack = input;
    drop_excluded_contours(stack);
    RepairLog log;
    auto valid = validate_contour_stack(stack, source_path, options.repair, log);
    if (!valid) return valid.error();  // the one line to show; repairs before it do not matter then
    if (options.warning)
        for (const auto& w : log.lines) options.warning(w);
    if (options.repair_counts) options.repair_counts(log.counts);

    // Stage 2: structures (labels, or correspondence for unlabelled contours).
    StructureGroups grouping = group_structures(stack, options.correspondence);

    // Stage 3: one mesh per structure, options.jobs at a time (structures are
    // independent). Results keep the structure order; the first error in that
    // order is the one reported, as in a one-thread build.
    std::vector<size_t> todo;
    for (size_t i = 0; i < grouping.infos.size(); ++i) {
        const auto& m = grouping.members[i];
        if (std::any_of(m.begin(), m.end(), [](const auto& v) { return !v.empty(); })) todo.push_back(i);
    }
    const size_t total = todo.size() * stack.slices.size();
    size_t done = 0;
    std::mutex progress_mutex;
    const std::function<void()> advance = [&] {
        if (!options.progress) return;
        std::lock_guard<std::mutex> lock(progress_mutex);
        options.progress(++done, total);
    };
    std::vector<std::optional<Result<StructureMesh>>> results(todo.size());
    std::atomic<size_t> next{0};
    std::atomic<bool> failed{false};
    const size_t threads = std::min<size_t>(std::max(options.jobs, 1u), todo.size());
    const unsigned inner_threads = std::max(1u, std::max(options.jobs, 1u) / unsigned(std::max<size_t>(threads, 1)));
    auto worker = [&] {
        // Indices are taken in increasing order, so after a failure every
        // structure before it has been taken and finishes: nothing later is needed.
        for (size_t k = next++; k < todo.size() && !failed; k = next++) {
            results[k] = build_structure(stack, grouping, todo[k], options, source_path, advance, inner_threads);
            if (!results[k]->ok()) failed = true;
        }
    };
    if (threads <= 1) {
        worker();
    } else {
        std::vector<std::thread> pool;
        for (size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
        for (auto& t : pool) t.join();
    }
    std::vector<StructureMesh> out;
    for (auto& r : results) {
        if (!r) break;  // not taken: only after a failure, which comes first in this order
        if (!r->ok()) return r->error();
        out.push_back(std::move(r->value()));
    }
    return out;
}

}  // namespace body
