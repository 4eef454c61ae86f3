// Quadric-error simplification recorded as vertex splits.
//
// References:
//   M. Garland, P. Heckbert, "Surface Simplification Using Quadric Error Metrics", SIGGRAPH 1997.
//   H. Hoppe, "Progressive Meshes", SIGGRAPH 1996.
//   T. Dey, H. Edelsbrunner, S. Guha, D. Nekhayev, "Topology preserving edge contraction", 1999
//     (the link condition).
//   P. Lindstrom, G. Turk, "Fast and Memory Efficient Polygonal Simplification", IEEE Visualization
//     1998 (quadrics from the current mesh rather than the accumulated input: restart_ordering).
//
// Pipeline (phases by file; their shared state is simplify_state.h; the public
// entry, build_progressive_mesh, is at the bottom of this file):
//   simplify_setup.cpp
//     clean_input      drop degenerate triangles and unreferenced vertices
//     build_adjacency  per-vertex corner lists (singly linked through corners), the face across each
//                      edge (kept up to date by the collapses), boundary/non-manifold flags
//     reorder_vertices, reorder_faces  renumber for cache locality (the output keeps the input numbering)
//     init_quadrics    area-weighted plane quadrics + boundary penalty planes (ordering) and unit-weight
//                      quadrics (the stored object-space error), gathered per vertex (a range of them:
//                      two halves on two threads)
//   collapse_checks.cpp
//     topology_allowed, geometry_allowed  whether a collapse may be applied
//   collapse_loop.cpp
//     placement        optimal (quadric minimiser) or fallback position of a collapse
//     lossless_regions a large mesh's lossless phase in independent regions, on threads
//     collapse_loop    indexed 4-ary heap of vertices keyed by their cheapest outgoing collapse
//                      (ordering cost per unit quadric weight)
//     restart_ordering at the end of the lossless phase, ordering quadrics from the current faces
//   simplify.cpp
//     emit_order       vertices and faces in refinement order, index patches per split
#include "builder/lod/simplify.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <future>
#include <vector>

#include "builder/lod/simplify_state.h"
#include "builder/lod/split_order.h"
#include "shared/pm/bpm_container.h"
#include "shared/pm/quantize.h"

namespace body::lod {

using namespace detail;

namespace {

void area_weighted_normals(std::span<const Vec3> pos, std::span<const uint32_t> idx, std::span<Vec3> n) {
    std::fill(n.begin(), n.end(), Vec3(0.0));
    for (size_t f = 0; f + 2 < idx.size(); f += 3) {
        const Vec3 c = glm::cross(pos[idx[f + 1]] - pos[idx[f]], pos[idx[f + 2]] - pos[idx[f]]);
        for (int k = 0; k < 3; ++k) n[idx[f + k]] += c;
    }
    for (Vec3& v : n) {
        const double l = glm::length(v);
        v = l > 0.0 ? v / l : Vec3(0.0, 0.0, 1.0);
    }
}

ProgressiveBuild emit_order(const State& s, const PrefaultedVector<Vec3>& normals) {
    ProgressiveBuild pm;
    const size_t n = s.pos.size(), faces = s.idx.size() / 3, splits = s.collapses.size();
    PrefaultedVector<uint32_t> vid(n, kNone), fid(faces, kNone);
    uint32_t next_v = 0, next_f = 0;
    for (const uint32_t v : s.vertex_of_input)
        if (s.alive[v]) vid[v] = next_v++;
    pm.base_vertices = next_v;
    for (const uint32_t f : s.face_of_input)
        if (s.face_alive[f]) fid[f] = next_f++;
    pm.base_faces = next_f;
    for (size_t j = 0; j < splits; ++j) {
        const Collapse& c = s.collapses[splits - 1 - j];
        vid[c.from] = next_v++;
        for (uint32_t i = 0; i < c.removed_count; ++i) fid[c.removed[i]] = next_f++;
    }
    pm.positions.resize(next_v);
    pm.normals.resize(next_v);
    for (size_t v = 0; v < n; ++v) {
        if (vid[v] == kNone) continue;
        pm.positions[vid[v]] = s.pos[v];
        pm.normals[vid[v]] = normals[v];
    }
    pm.indices.resize(size_t(next_f) * 3);
    for (size_t f = 0; f < faces; ++f) {
        if (fid[f] == kNone) continue;
        for (int k = 0; k < 3; ++k) pm.indices[fid[f] * 3 + k] = vid[s.idx[f * 3 + k]];
    }
    pm.splits.resize(splits);
    pm.patch_begin.assign(splits + 1, 0);
    pm.patch_faces.reserve(s.patch_faces.size());
    for (size_t j = 0; j < splits; ++j) {
        const Collapse& c = s.collapses[splits - 1 - j];
        pm.splits[j] = {vid[c.to], c.removed_count, c.error, c.to_after, c.to_before};
        for (uint32_t i = c.patch_begin; i < c.patch_end; ++i) pm.patch_faces.push_back(fid[s.patch_faces[i]]);
        pm.patch_begin[j + 1] = uint32_t(pm.patch_faces.size());
    }
    return pm;
}

}  // namespace

Result<ProgressiveBuild> build_progressive_mesh(const Mesh& mesh, const LodOptions& options) {
    Surface m;
    PrefaultedVector<uint32_t> kept;
    clean_input(mesh, m, kept);
    if (m.idx.empty()) return input_error("lod: mesh '" + mesh.name + "' has no non-degenerate triangles");
    if (m.pos.size() > pm::kMaxVertices || m.idx.size() / 3 > pm::kMaxFaces)
        return input_error("lod: mesh '" + mesh.name + "' has more than " + std::to_string(pm::kMaxVertices) +
                           " vertices or " + std::to_string(pm::kMaxFaces) + " triangles");
    PrefaultedVector<Vec3> normals(m.pos.size());
    if (mesh.normals.size() == mesh.positions.size()) {
        for (size_t i = 0; i < kept.size(); ++i) {
            const double l = glm::length(mesh.normals[kept[i]]);
            normals[i] = l > 0.0 ? mesh.normals[kept[i]] / l : Vec3(0, 0, 1);
        }
    } else {
        area_weighted_normals(m.pos, m.idx, normals);
    }
    const unsigned threads = thread_count(options);
    // Runs `side` on a second thread while the caller runs `here` (both in turn on one
    // thread). The output is the same bytes.
    auto beside = [threads](auto&& here, auto&& side) {
        if (threads < 2) {
            here();
            side();
            return;
        }
        std::future<void> done = std::async(std::launch::async, side);
        here();
        done.get();
    };
    const size_t n = m.pos.size(), corners = m.idx.size();
    PrefaultedVector<Collapse> collapses;
    PrefaultedVector<uint32_t> patch_faces;
    beside(
        [&] {
            build_adjacency(m);
            reorder_vertices(m, normals);
            // After both renumberings (nothing to permute), summed in the input's face order.
            reorder_faces(m);
        },
        [&] {
            // The collapse loop's own arrays meanwhile (mapping them is a good part of their cost).
            m.key.resize(n);
            m.corner_cost.assign(corners, kNoCost);
            m.mark.assign(n, 0);
            m.q.resize(n);
            m.e.resize(n);
            // At most one collapse per vertex, each moving a few faces: no regrowth (copies) in the loop.
            collapses.reserve(n);
            // (Patches move 3.5-3.8 faces per collapse on the bunny and its subdivision; the
            // storage is mapped when reserved, so the margin is kept small.)
            patch_faces.reserve(n * 5);
        });
    // Each vertex's sums are its own: two halves at once give the same bits.
    beside([&] { init_quadrics(m, options.boundary_weight, 0, uint32_t(n / 2)); },
           [&] { init_quadrics(m, options.boundary_weight, uint32_t(n / 2), uint32_t(n)); });
    const Aabb box = mesh_bounds(m.pos);
    m.settings.optimal = options.optimal_placement;
    m.settings.boundary_weight = options.boundary_weight;
    m.settings.lossless_distance = kLosslessDistance * box.extent();
    m.settings.lossless_cost = m.settings.lossless_distance * m.settings.lossless_distance;
    m.settings.box_min = box.min;
    m.settings.box_max = box.max;
    Vec3 grid_step{0.0};
    for (int k = 0; k < 3; ++k) {
        m.settings.grid_lo[k] = pm::float_at_or_below(box.min[k]);
        m.settings.grid_hi[k] = pm::float_at_or_above(box.max[k]);
        grid_step[k] = pm::quantization_step(m.settings.grid_lo[k], m.settings.grid_hi[k]);
    }
    m.settings.grid_reach2 = 4.0 * glm::dot(grid_step, grid_step);

    State s(m);
    s.collapses.swap(collapses);
    s.patch_faces.swap(patch_faces);
    collapse_loop(m, s, std::max<size_t>(options.min_triangles, 1), options);
    ProgressiveBuild out = emit_order(s, normals);
    if (options.batch_rounds) order_splits_in_batches(out);
    return out;
}

Mesh extract_level(const ProgressiveBuild& pm, size_t level) {
    level = std::min(level, pm.splits.size());
    size_t faces = pm.base_faces;
    for (size_t j = 0; j < level; ++j) faces += pm.splits[j].face_count;
    Mesh m;
    m.positions.assign(pm.positions.begin(), pm.positions.begin() + ptrdiff_t(pm.base_vertices + level));
    m.indices.assign(pm.indices.begin(), pm.indices.begin() + ptrdiff_t(faces * 3));
    // Faces are stored as they are when they appear; replay the index patches.
    for (size_t j = 0; j < level; ++j) {
        const uint32_t child = uint32_t(pm.base_vertices + j), parent = pm.splits[j].parent;
        for (uint32_t i = pm.patch_begin[j]; i < pm.patch_begin[j + 1]; ++i) {
            uint32_t* t = &m.indices[size_t(pm.patch_faces[i]) * 3];
            for (int k = 0; k < 3; ++k)
                if (t[k] == parent) t[k] = child;
        }
        m.positions[parent] = pm.splits[j].parent_to;
    }
    return m;
}

}  // namespace body::lod
