// Progressive meshes side by side with meshoptimizer (and VTK through
// bench/pm_vs_vtk.sh), on the bunny (glmark2-data) and the bunny subdivided
// twice (~1.1M triangles). Every figure is printed with its ratio against a
// baseline measured in the same run (times are thread CPU seconds, best of N, except
// the builds: see 1):
//   1. full PM build (simplify to the end + encode .bpm) vs meshopt_simplify making
//      a 10-level chain (100% -> 1%, each level from the previous)       goal <= 1.0
//      (one of each per round; also the median and range of the per-round ratios).
//      Wall time (a large mesh's lossless phase runs on several threads), and the CPU
//      time of all threads beside it (what the threads cost).
//   2. symmetric sampled Hausdorff at 10% and 2% of the triangles, ours vs the better
//      of meshopt_simplify and vtkQuadricDecimation, all three at the same triangle
//      count                                                              goal <= 1.0
//      (and the same build with half-edge collapses only, for comparison)
//   3. runtime: vertex splits per second, full coarse -> fine sweep time (vs one
//      memcpy of the full index array), decoding the whole file (vs meshopt decoding
//      the full mesh as one vertex + index buffer), bytes per vertex split (goal <= 10 B)
//
// usage: bench_pm [--obj FILE] [--mesh NAME=FILE]... [--vtk-dir DIR] [--write-dir DIR] [--no-big] [--build-only]
//                 [--accuracy-only] [--ours-only]
//                 [--reps N] [--big-reps N] [--threads N] [--no-regions] [--exact-intermediate]
//                 [--decode FILE.bpm]
//   --build-only prints the build times only (section 1); --accuracy-only prints section 2 only (one build,
//   no half-edge comparison build, no runtime) and the bytes per split; --reps N: best of N for the bunny (default 3;
//   the big mesh gets best of --big-reps, default 1) -- on a busy machine a larger N finds the quiet runs;
//   --threads N: threads of the build (default: one per hardware thread; the output is the same);
//   --no-regions: the lossless phase on one heap, as before it ran in regions (a different output);
//   --exact-intermediate: every position exact (as .bpm version 5), not intermediate ones on grids (FORMAT.md);
//   --ours-only: section 2 for ours alone at the same counts (VTK's files still set them), for trying
//   simplifier changes without the baselines' minutes on a big mesh;
//   --decode times reading one .bpm (nothing else);
//   --mesh NAME=FILE also runs every section on that OBJ (e.g. bench/loop_bunny.py's 1.1M bunny, a region
//   built by `bodygen build`), labelled NAME;
//   --write-dir writes the inputs (bunny.obj, bunny_sub.obj, NAME.obj) for the VTK script;
//   --vtk-dir reads DIR/<name>_vtk_<percent>.obj written by vtkQuadricDecimation.
#include <benchmark/benchmark.h>
#include <meshoptimizer.h>
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "builder/lod/bpm_writer.h"
#include "builder/lod/codec_baselines.h"
#include "builder/lod/hausdorff.h"
#include "builder/lod/simplify.h"
#include "shared/atomic_file.h"
#include "shared/obj_io.h"
#include "shared/pm/bpm_container.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "shared/pm/quantize.h"

namespace {

using namespace body;
lod::LodOptions g_options;  // --threads, --no-regions, --exact-intermediate
bool g_ours_only = false;   // --ours-only
// CPU seconds of this thread: the build machine is shared, so wall time is
// inflated by other people's work; every timed piece here is single-threaded.
double cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Wall and all-thread CPU seconds.
struct Clocks {
    double wall, cpu;
};
Clocks clocks() {
    timespec w{}, c{};
    clock_gettime(CLOCK_MONOTONIC, &w);
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c);
    return {double(w.tv_sec) + 1e-9 * double(w.tv_nsec), double(c.tv_sec) + 1e-9 * double(c.tv_nsec)};
}
template <typename F>
Clocks timed(F&& f) {
    const Clocks t0 = clocks();
    f();
    const Clocks t1 = clocks();
    return {t1.wall - t0.wall, t1.cpu - t0.cpu};
}

template <typename F>
double best_time(int reps, F&& f) {
    double best = 1e300;
    for (int i = 0; i < reps; ++i) {
        const double t0 = cpu_seconds();
        f();
        best = std::min(best, cpu_seconds() - t0);
    }
    return best;
}

Mesh subdivide(const Mesh& in) {
    Mesh out;
    out.name = in.name + "_sub";
    out.positions = in.positions;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
        auto key = std::minmax(a, b);
        auto [it, inserted] = mid.emplace(key, uint32_t(out.positions.size()));
        if (inserted) out.positions.push_back((in.positions[a] + in.positions[b]) * 0.5);
        return it->second;
    };
    for (size_t f = 0; f < in.indices.size(); f += 3) {
        uint32_t a = in.indices[f], b = in.indices[f + 1], c = in.indices[f + 2];
        uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        out.indices.insert(out.indices.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    return out;
}

std::vector<float> float_positions(const Mesh& m) {
    std::vector<float> p;
    for (const Vec3& v : m.positions) p.insert(p.end(), {float(v.x), float(v.y), float(v.z)});
    return p;
}

// meshopt_simplify from the full mesh to `target` triangles, no error limit.
std::vector<uint32_t> meshopt_level(const Mesh& m, const std::vector<float>& fp, size_t target) {
    std::vector<uint32_t> out(m.indices.size());
    out.resize(meshopt_simplify(out.data(), m.indices.data(), m.indices.size(), fp.data(), m.positions.size(), 12,
                                target * 3, 1.0f, 0, nullptr));
    return out;
}

void meshopt_chain(const Mesh& m, const std::vector<float>& fp) {
    std::vector<uint32_t> cur = m.indices, next(m.indices.size());
    for (int level = 1; level <= 10; ++level) {
        const double ratio = std::pow(0.01, level / 10.0);
        const size_t target = size_t(double(m.indices.size() / 3) * ratio) * 3;
        next.resize(cur.size());
        next.resize(meshopt_simplify(next.data(), cur.data(), cur.size(), fp.data(), m.positions.size(), 12, target,
                                     1.0f, 0, nullptr));
        cur.swap(next);
    }
}

struct SectionBytes {
    size_t base = 0, splits = 0, other = 0;
};
SectionBytes section_bytes(const std::vector<uint8_t>& b) {
    SectionBytes s;
    size_t pos = pm::kFileHeaderSize;
    s.other += pos;
    while (pos + pm::kSectionHeaderSize <= b.size()) {
        const uint32_t tag = pm::get_u32(&b[pos]), len = pm::get_u32(&b[pos + 8]);
        const size_t total = pm::kSectionHeaderSize + len + pm::kSectionTrailerSize;
        (tag == pm::kTagSplits ? s.splits : tag == pm::kTagBase ? s.base : s.other) += total;
        pos += total;
    }
    return s;
}

void row(const char* what, double ours, const char* base_name, double base) {
    std::printf("  %-44s %12.6g   %-30s %12.6g   ratio %7.3f\n", what, ours, base_name, base, ours / base);
}

void run(const Mesh& mesh, const std::string& label, const std::string& vtk_dir, int reps, bool build_only,
         bool accuracy_only) {
    const size_t tris = mesh.triangle_count();
    std::printf("\n== %s: %zu vertices, %zu triangles\n", label.c_str(), mesh.positions.size(), tris);
    const std::vector<float> fp = float_positions(mesh);
    const std::vector<Mesh> one{mesh};

    // 1. build time
    std::vector<uint8_t> bytes;
    lod::LodOptions options = g_options;
    if (g_ours_only) options.batch_rounds = false;  // one build serves both readings
    if (accuracy_only) {
        bytes = *lod::encode_bpm(one, options);
    } else {
        // Interleaved, one of each per round: this VM's speed (its page-fault cost above all)
        // drifts over minutes, so a block of ours then a block of theirs can measure two
        // different machines. Best times, and the spread of the per-round ratios.
        std::vector<double> pm_ratio, simplify_ratio;
        Clocks t_pm{1e300, 1e300}, t_simplify = t_pm, t_chain = t_pm;
        auto keep_best = [](Clocks& best, Clocks t) {
            best.wall = std::min(best.wall, t.wall);
            best.cpu = std::min(best.cpu, t.cpu);
        };
        for (int r = 0; r < reps; ++r) {
            const Clocks pm_r = timed([&] { bytes = *lod::encode_bpm(one, options); });
            const Clocks simplify_r = timed([&] { (void)lod::build_progressive_mesh(mesh, options); });
            const Clocks chain_r = timed([&] { meshopt_chain(mesh, fp); });
            keep_best(t_pm, pm_r);
            keep_best(t_simplify, simplify_r);
            keep_best(t_chain, chain_r);
            pm_ratio.push_back(pm_r.wall / chain_r.wall);
            simplify_ratio.push_back(simplify_r.wall / chain_r.wall);
        }
        std::printf(" build (wall seconds; CPU seconds of all threads below each)\n");
        row("PM build + encode (s)", t_pm.wall, "meshopt 10-level chain (s)", t_chain.wall);
        row("  CPU (s)", t_pm.cpu, "CPU (s)", t_chain.cpu);
        row("  of which simplification (s)", t_simplify.wall, "meshopt 10-level chain (s)", t_chain.wall);
        row("    CPU (s)", t_simplify.cpu, "CPU (s)", t_chain.cpu);
        auto spread = [](const char* what, std::vector<double> r) {
            std::sort(r.begin(), r.end());
            std::printf("  %-44s median %.3f, min %.3f, max %.3f over %zu rounds\n", what, r[r.size() / 2], r.front(),
                        r.back(), r.size());
        };
        spread("per-round ratio, PM build + encode", pm_ratio);
        spread("per-round ratio, simplification", simplify_ratio);
    }
    if (build_only) return;

    auto pms = pm::read_bpm_bytes(bytes, label);
    if (!pms) {
        std::printf("read failed: %s\n", pms.error().message.c_str());
        return;
    }
    pm::ProgressiveMesh& m = *(*pms)[0];
    std::printf("  levels: %zu splits, base %zu triangles (%.3f%%)\n", m.max_level(), m.base_triangle_count(),
                100.0 * double(m.base_triangle_count()) / double(tris));

    // 2. accuracy, every method at the same triangle count: vtkQuadricDecimation's output (a
    // target reduction, so about the percentage) fixes the count when it is there, else the
    // percentage does; ours and meshopt_simplify stop at or below it. Ours is read in
    // refinement order from a build whose splits stay in error order (batch_rounds off), so
    // any count is an exact prefix; the kiosk's batched file draws only its batch boundaries,
    // whose meshes are the same (split_order.h), and is shown beside it at the nearest
    // boundary below the count (the level the kiosk draws when asked for that many).
    std::printf(" accuracy (symmetric sampled Hausdorff, object units; bbox diagonal %g)\n",
                mesh_bounds(mesh.positions).extent());
    lod::SurfaceDistance full(mesh.positions, mesh.indices);
    auto distance = [&](const std::vector<Vec3>& ps, const std::vector<uint32_t>& idx) {
        return std::max(lod::one_sided_hausdorff(ps, idx, full),
                        lod::one_sided_hausdorff(mesh.positions, mesh.indices, lod::SurfaceDistance(ps, idx)));
    };
    auto hausdorff_at_level = [&](pm::ProgressiveMesh& pmesh, size_t level) {
        pmesh.set_level(level);
        std::vector<Vec3> pos;
        for (size_t v = 0; v < pmesh.vertex_count(); ++v) pos.push_back(Vec3(pmesh.position(v)));
        std::vector<uint32_t> idx(pmesh.indices().begin(),
                                  pmesh.indices().begin() + ptrdiff_t(pmesh.triangle_count() * 3));
        return distance(pos, idx);
    };
    auto hausdorff_at = [&](pm::ProgressiveMesh& pmesh, size_t target) {
        return hausdorff_at_level(pmesh, pmesh.level_for_triangles(target));
    };
    lod::LodOptions by_error = options;
    by_error.batch_rounds = false;
    const std::vector<uint8_t> exact_bytes = options.batch_rounds ? *lod::encode_bpm(one, by_error) : bytes;
    auto exact_pms = pm::read_bpm_bytes(exact_bytes, label, pm::BpmStream::FaceOrder::Refinement);
    if (!exact_pms) {
        std::printf("read failed: %s\n", exact_pms.error().message.c_str());
        return;
    }
    pm::ProgressiveMesh& exact = *(*exact_pms)[0];
    // The same build with half-edge collapses only (no optimal placement), for comparison.
    lod::LodOptions half_edge = by_error;
    half_edge.optimal_placement = false;
    // Its size too: a half-edge split stores no parent move (what the optimal placement costs in bytes).
    std::vector<uint8_t> he_bytes;
    if (!accuracy_only) he_bytes = *lod::encode_bpm(one, half_edge);
    auto he_pms = accuracy_only ? Result<std::vector<std::unique_ptr<pm::ProgressiveMesh>>>(
                                      input_error("bench_pm: half-edge build skipped (--accuracy-only)"))
                                : pm::read_bpm_bytes(he_bytes, label, pm::BpmStream::FaceOrder::Refinement);
    if (he_pms)
        row("bytes per split (whole file, splits by error)", double(exact_bytes.size()) / double(exact.max_level()),
            "ours, half-edge collapses only", double(he_bytes.size()) / double((*he_pms)[0]->max_level()));
    for (double pct : {10.0, 2.0}) {
        double vtk = -1.0;
        size_t vtk_tris = 0;
        std::vector<Vec3> vtk_positions;
        std::vector<uint32_t> vtk_indices;
        const std::string vtk_file = vtk_dir + "/" + label + "_vtk_" + std::to_string(int(pct)) + ".obj";
        if (!vtk_dir.empty() && std::filesystem::exists(vtk_file)) {
            if (auto v = read_obj_merged(vtk_file)) {
                vtk_tris = v->triangle_count();
                vtk = g_ours_only ? 0.0 : distance(v->positions, v->indices);
                vtk_positions = std::move(v->positions);
                vtk_indices = std::move(v->indices);
            }
        }
        const size_t target = vtk >= 0 ? vtk_tris : size_t(double(tris) * pct / 100.0);
        const double ours = hausdorff_at(exact, target);
        const size_t ours_tris = exact.triangle_count();
        if (g_ours_only) {
            std::printf("  at %g%%: count %zu; ours %zu tris, Hausdorff %.6g, stored error %.6g\n", pct, target,
                        ours_tris, ours, double(exact.error_at(exact.level())));
            continue;
        }
        const std::vector<uint32_t> mo = meshopt_level(mesh, fp, target);
        const double mopt = distance(mesh.positions, mo);
        std::printf("  at %g%%: count %zu; ours %zu tris, meshopt %zu tris, vtk %s\n", pct, target, ours_tris,
                    mo.size() / 3,
                    vtk < 0 ? "not run (bench/pm_vs_vtk.sh)" : (std::to_string(vtk_tris) + " tris").c_str());
        row("ours Hausdorff", ours, "meshopt_simplify", mopt);
        if (vtk >= 0) row("ours Hausdorff", ours, "vtkQuadricDecimation", vtk);
        const double best = vtk >= 0 ? std::min(mopt, vtk) : mopt;
        row("ours Hausdorff", ours, vtk >= 0 ? "better of meshopt/vtk" : "meshopt (no vtk)", best);
        // Ours is read back from the .bpm, whose positions sit on a 16-bit grid in
        // the bounding box (the format); the others keep floats. The same
        // comparison with their vertices snapped to that grid separates the
        // simplifier's accuracy from the format's quantization.
        {
            const Vec3f lo = exact.bounds_min(), hi = exact.bounds_max();
            auto on_grid = [&](const std::vector<Vec3>& ps) {
                std::vector<Vec3> out(ps.size());
                for (size_t i = 0; i < ps.size(); ++i)
                    for (int k = 0; k < 3; ++k) {
                        const double range = double(hi[k]) - double(lo[k]);
                        const double t = range > 0 ? std::nearbyint((ps[i][k] - double(lo[k])) / range * 65535.0) : 0.0;
                        out[i][k] = double(pm::dequantize16(uint16_t(std::clamp(t, 0.0, 65535.0)), lo[k], hi[k]));
                    }
                return out;
            };
            double grid_best = distance(on_grid(mesh.positions), mo);
            if (vtk >= 0) grid_best = std::min(grid_best, distance(on_grid(vtk_positions), vtk_indices));
            row("ours Hausdorff", ours, vtk >= 0 ? "better, on our 16-bit grid" : "meshopt, on our 16-bit grid",
                grid_best);
        }
        // Positions are 16-bit quantized: the stored error bounds the distance together
        // with the quantization bound (which dominates on nearly flat levels).
        const double bound = double(exact.error_at(exact.level())) + double(exact.quantization_bound());
        std::printf("  %-44s %12.6g   (stored error %g + quantization %g; measured/bound %.3f)\n", "ours error bound",
                    bound, double(exact.error_at(exact.level())), double(exact.quantization_bound()), ours / bound);
        if (he_pms) {
            const double he = hausdorff_at(*(*he_pms)[0], target);
            row("ours Hausdorff", ours, "ours, half-edge collapses only", he);
            row("ours half-edge only Hausdorff", he, vtk >= 0 ? "better of meshopt/vtk" : "meshopt (no vtk)", best);
        }
        // The level the kiosk draws when asked for that many triangles (a batch boundary).
        const size_t drawn = m.level_for_triangles(target);
        const double ours_drawn = hausdorff_at_level(m, drawn);
        const std::vector<uint32_t> mo_drawn = meshopt_level(mesh, fp, m.triangle_count());
        char what[64];
        std::snprintf(what, sizeof what, "kiosk's level: %zu tris, Hausdorff", m.triangle_count());
        row(what, ours_drawn, "meshopt_simplify, same count", distance(mesh.positions, mo_drawn));
    }

    if (accuracy_only) {
        const SectionBytes sb = section_bytes(bytes);
        row("bytes per vertex split (SPLT sections)", double(sb.splits) / double(m.max_level()), "goal", 10.0);
        return;
    }
    // 3. runtime
    std::printf(" runtime\n");
    const size_t n = m.max_level();
    // Each direction timed on its own, best of several sweeps.
    double t_up = 1e300, t_down = 1e300;
    for (int i = 0; i < reps * 3; ++i) {
        double t0 = cpu_seconds();
        m.refine_to(n);
        t_up = std::min(t_up, cpu_seconds() - t0);
        t0 = cpu_seconds();
        m.coarsen_to(0);
        t_down = std::min(t_down, cpu_seconds() - t0);
    }
    std::vector<uint32_t> copy(m.indices().size());
    const double t_memcpy = best_time(reps * 3, [&] {
        std::memcpy(copy.data(), m.indices().data(), copy.size() * 4);
        benchmark::DoNotOptimize(copy.data());
        benchmark::ClobberMemory();
    });
    row("splits/s refining (M)", double(n) / t_up / 1e6, "splits/s coarsening (M)", double(n) / t_down / 1e6);
    row("full coarse->fine sweep (ms)", t_up * 1e3, "memcpy of full index array (ms)", t_memcpy * 1e3);
    // Decoding the whole file (what the kiosk does while the detail streams in) vs
    // decoding the full mesh sent as one meshopt vertex + index buffer (same codecs,
    // no progressive structure): the price of the vertex-split replay.
    double t_decode = best_time(reps * 2, [&] {
        auto again = pm::read_bpm_bytes(bytes, label);
        benchmark::DoNotOptimize(again);
    });
    std::vector<pm::BaseVertex> flat_v(m.max_vertex_count());
    std::vector<uint32_t> flat_i(m.indices().begin(), m.indices().end());
    for (size_t v = 0; v < flat_v.size(); ++v) flat_v[v] = {{uint16_t(v), uint16_t(v >> 16), 0}, {0, 0}};
    std::vector<uint8_t> enc_v(meshopt_encodeVertexBufferBound(flat_v.size(), sizeof(pm::BaseVertex)));
    enc_v.resize(
        meshopt_encodeVertexBuffer(enc_v.data(), enc_v.size(), flat_v.data(), flat_v.size(), sizeof(pm::BaseVertex)));
    std::vector<uint8_t> enc_i(meshopt_encodeIndexBufferBound(flat_i.size(), flat_v.size()));
    enc_i.resize(meshopt_encodeIndexBuffer(enc_i.data(), enc_i.size(), flat_i.data(), flat_i.size()));
    const double t_flat = best_time(reps * 2, [&] {
        (void)meshopt_decodeVertexBuffer(flat_v.data(), flat_v.size(), sizeof(pm::BaseVertex), enc_v.data(),
                                         enc_v.size());
        (void)meshopt_decodeIndexBuffer(flat_i.data(), flat_i.size(), 4, enc_i.data(), enc_i.size());
        benchmark::DoNotOptimize(flat_i.data());
    });
    row("decode whole .bpm (ms)", t_decode * 1e3, "meshopt decode of full mesh (ms)", t_flat * 1e3);
    std::printf("  %-44s %12.6g\n", "splits decoded/s (M)", double(n) / t_decode / 1e6);
    const SectionBytes sb = section_bytes(bytes);
    row("bytes per vertex split (SPLT sections)", double(sb.splits) / double(n), "goal", 10.0);
    row("bytes per vertex split (whole file)", double(bytes.size()) / double(n), "goal", 10.0);
    const double raw = double(n) * (6 + 2 + 4 + 4) + double(m.max_triangle_count() - m.base_triangle_count()) * 12 +
                       4.0 * 4 * double(n);
    row("SPLT bytes", double(sb.splits), "uncompressed records", raw);
}

// The fewest vertex transforms per triangle any order inside the batched
// layout's runs can reach at the mesh's current level: each run (the base, then
// each batch's faces: one cache-ordered run apiece) transforms every vertex it
// uses at least once, so the floor is the sum of the runs' distinct vertices
// over the triangles (a static mesh's floor: its vertices over its triangles).
double prefix_layout_floor(const pm::ProgressiveMesh& m, const std::vector<uint32_t>& indices) {
    std::vector<size_t> run_ends{m.triangles_at(0)};
    for (uint32_t level : m.batch_levels())
        if (level <= m.level()) run_ends.push_back(m.triangles_at(level));
    std::vector<size_t> last_run(m.vertex_count(), SIZE_MAX);
    size_t transforms = 0, begin = 0;
    for (size_t r = 0; r < run_ends.size(); ++r) {
        for (size_t i = begin * 3; i < run_ends[r] * 3; ++i)
            if (last_run[indices[i]] != r) {
                last_run[indices[i]] = r;
                ++transforms;
            }
        begin = run_ends[r];
    }
    return double(transforms) / double(std::max<size_t>(1, indices.size() / 3));
}

// Vertex cache misses per triangle (ACMR, cache of 16) and vertex fetch overfetch
// (64-byte lines of the kiosk's 16-byte vertices) at the batch boundary levels
// nearest 100, 40 and 10 % of the triangles: the batched order, the refinement
// order, and the same triangles through meshopt (cache then fetch order).
void print_locality(std::span<const uint8_t> bytes, const std::string& path) {
    auto batched = pm::read_bpm_bytes(bytes, path, pm::BpmStream::FaceOrder::Batched);
    auto plain = pm::read_bpm_bytes(bytes, path, pm::BpmStream::FaceOrder::Refinement);
    if (!batched || !plain || batched->empty()) return;
    pm::ProgressiveMesh &a = *batched->front(), &b = *plain->front();
    const auto prefix = [](const pm::ProgressiveMesh& m) {
        return std::vector<uint32_t>(m.indices().begin(), m.indices().begin() + ptrdiff_t(m.triangle_count() * 3));
    };
    for (double share : {1.0, 0.4, 0.1}) {
        const size_t level = a.level_for_triangles(size_t(share * double(a.max_triangle_count())));
        a.set_level(level);
        b.set_level(level);
        const auto ia = prefix(a), ib = prefix(b);
        const size_t nv = a.vertex_count();
        std::vector<uint32_t> is(ia.size()), remap(nv);
        meshopt_optimizeVertexCache(is.data(), ia.data(), ia.size(), nv);
        const size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), is.data(), is.size(), nv);
        meshopt_remapIndexBuffer(is.data(), is.data(), is.size(), remap.data());
        const auto cache = [&](const std::vector<uint32_t>& i, size_t n) {
            return meshopt_analyzeVertexCache(i.data(), i.size(), n, 16, 0, 0).acmr;
        };
        const auto fetch = [&](const std::vector<uint32_t>& i, size_t n) {
            return meshopt_analyzeVertexFetch(i.data(), i.size(), n, 16).overfetch;
        };
        std::printf(
            "  %3.0f%% (%zu triangles): ACMR batched %.3f refinement %.3f static %.3f; overfetch batched %.2f "
            "refinement %.2f static %.2f\n",
            share * 100, ia.size() / 3, cache(ia, nv), cache(ib, nv), cache(is, used), fetch(ia, nv), fetch(ib, nv),
            fetch(is, used));
        std::printf("        ACMR floor: batched runs %.3f, static mesh %.3f\n", prefix_layout_floor(a, ia),
                    double(used) / double(ia.size() / 3));
    }
}

// --decode: CPU time of reading one file (best of 5), split by phase.
int decode_only(const std::string& path) {
    auto data = read_file(path);
    if (!data) {
        std::fprintf(stderr, "bench_pm: %s\n", data.error().message.c_str());
        return 1;
    }
    const std::span<const uint8_t> bytes(reinterpret_cast<const uint8_t*>(data->data()), data->size());
    size_t splits = 0;
    const auto timed = [&](pm::BpmStream::FaceOrder order) {
        return best_time(5, [&] {
            auto pms = pm::read_bpm_bytes(bytes, path, order);
            splits = 0;
            if (pms)
                for (auto& m : *pms) splits += m->max_level();
        });
    };
    // The kiosk's batched draw order against the file's order (no reordering), same run.
    const double t = timed(pm::BpmStream::FaceOrder::Batched), plain = timed(pm::BpmStream::FaceOrder::Refinement);
    std::printf(
        "%s: %zu bytes, %zu splits decoded in %.1f ms (%.2f M splits/s); in refinement order %.1f ms (batched order "
        "costs %.2fx)\n",
        path.c_str(), bytes.size(), splits, t * 1e3, double(splits) / t / 1e6, plain * 1e3, t / plain);
    print_locality(bytes, path);
    // Size: the file per split beside the full mesh through static-mesh codecs
    // at the same quantization (codec_baselines.h).
    auto pms = pm::read_bpm_bytes(bytes, path, pm::BpmStream::FaceOrder::Refinement);
    if (pms && pms->size() == 1) {
        pm::ProgressiveMesh& m = *pms->front();
        m.set_level(m.max_level());
        const auto idx = m.indices().first(m.max_triangle_count() * 3);
        const uint8_t* oct = m.has_normals() ? m.normal_codes().data() : nullptr;
        const size_t nv = m.max_vertex_count();
        const auto per_vertex = [&](size_t b) { return double(b) / double(nv); };
        std::printf("  size: %.2f bytes per split; full mesh per vertex: meshopt codecs %.2f, Draco %.2f (%s)\n",
                    double(bytes.size()) / double(std::max<size_t>(m.max_level(), 1)),
                    per_vertex(lod::meshopt_codec_bytes(m.position_codes().data(), oct, nv, idx.data(), idx.size())),
                    per_vertex(lod::draco_codec_bytes(m.position_codes().data(), oct, nv, idx.data(), idx.size())),
                    lod::draco_available() ? "level 10" : "not built in");
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    std::string obj = "/usr/share/glmark2/models/bunny.obj", vtk_dir, write_dir, decode;
    bool big = true, build_only = false, accuracy_only = false;
    int big_reps = 1;
    std::setvbuf(stdout, nullptr, _IOLBF, 0);  // each table row as it is measured (the big meshes take minutes)
    int reps = 3;
    std::vector<std::pair<std::string, std::string>> extra;  // --mesh NAME=FILE, in order
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--obj" && i + 1 < argc)
            obj = argv[++i];
        else if (a == "--mesh" && i + 1 < argc && std::strchr(argv[i + 1], '=')) {
            const std::string m = argv[++i];
            extra.emplace_back(m.substr(0, m.find('=')), m.substr(m.find('=') + 1));
        } else if (a == "--vtk-dir" && i + 1 < argc)
            vtk_dir = argv[++i];
        else if (a == "--write-dir" && i + 1 < argc)
            write_dir = argv[++i];
        else if (a == "--decode" && i + 1 < argc)
            decode = argv[++i];
        else if (a == "--no-big")
            big = false;
        else if (a == "--build-only")
            build_only = true;
        else if (a == "--accuracy-only")
            accuracy_only = true;
        else if (a == "--ours-only")
            accuracy_only = g_ours_only = true;
        else if (a == "--reps" && i + 1 < argc)
            reps = std::max(1, std::atoi(argv[++i]));
        else if (a == "--big-reps" && i + 1 < argc)
            big_reps = std::max(1, std::atoi(argv[++i]));
        else if (a == "--threads" && i + 1 < argc)
            g_options.threads = unsigned(std::max(1, std::atoi(argv[++i])));
        else if (a == "--no-regions")
            g_options.region_faces = SIZE_MAX;
        else if (a == "--exact-intermediate")
            g_options.coarse_intermediate = false;
        else {
            std::fprintf(
                stderr,
                "usage: bench_pm [--obj FILE] [--mesh NAME=FILE]... [--vtk-dir DIR] [--write-dir DIR] [--no-big] "
                "[--build-only] [--accuracy-only] [--ours-only] "
                "[--reps N] [--big-reps N] [--threads N] [--no-regions] [--exact-intermediate] [--decode FILE.bpm]\n");
            return 2;
        }
    }
    if (!decode.empty()) return decode_only(decode);
    auto mesh = body::read_obj_merged(obj);
    if (!mesh) {
        std::fprintf(stderr, "bench_pm: %s (Debian package glmark2-data)\n", mesh.error().message.c_str());
        return 1;
    }
    mesh->name = "bunny";
    body::Mesh sub;  // the big mesh, made only when it is used (subdividing takes seconds)
    if (big) {
        sub = subdivide(subdivide(*mesh));
        sub.name = "bunny_sub";
    }
    std::vector<body::Mesh> extra_meshes;
    for (const auto& [name, file] : extra) {
        auto e = body::read_obj_merged(file);
        if (!e) {
            std::fprintf(stderr, "bench_pm: %s\n", e.error().message.c_str());
            return 1;
        }
        e->name = name;
        extra_meshes.push_back(std::move(*e));
    }
    if (!write_dir.empty()) {
        (void)body::write_obj(write_dir + "/bunny.obj", std::vector<body::Mesh>{*mesh});
        if (big) (void)body::write_obj(write_dir + "/bunny_sub.obj", std::vector<body::Mesh>{sub});
        for (const body::Mesh& e : extra_meshes)
            (void)body::write_obj(write_dir + "/" + e.name + ".obj", std::vector<body::Mesh>{e});
        std::printf("wrote inputs to %s\n", write_dir.c_str());
        return 0;
    }
    std::printf(
        "bench_pm: ratios are ours / baseline, same run, same machine; times in thread CPU seconds except the "
        "builds'\n");
    run(*mesh, "bunny", vtk_dir, reps, build_only, accuracy_only);
    if (big) run(sub, "bunny_sub", vtk_dir, big_reps, build_only, accuracy_only);
    for (const body::Mesh& e : extra_meshes)
        run(e, e.name, vtk_dir, e.triangle_count() > 200000 ? big_reps : reps, build_only, accuracy_only);
    return 0;
}
