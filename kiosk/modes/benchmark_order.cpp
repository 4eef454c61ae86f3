// The benchmark's draw-order table (contract in benchmark.h): a .bpm level as
// the kiosk draws it against the same triangles as a static mesh that
// meshoptimizer ordered for the vertex cache and fetch, in the same run.
#include <GLES3/gl3.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "kiosk/modes/benchmark.h"
#include "kiosk/modes/gpu_timer.h"
#include "shared/pm/bpm_reader.h"

namespace body::kiosk {
namespace {

// The static mesh of one level: vertex cache order, then vertices in first-use
// order; the .bpm's own codes (same formats as the kiosk's model).
struct StaticLevel {
    std::vector<uint32_t> indices;
    std::vector<uint16_t> codes;
    std::vector<uint8_t> oct;
};

StaticLevel optimise(const pm::ProgressiveMesh& m) {
    StaticLevel s;
    const size_t n = m.triangle_count() * 3, vc = m.vertex_count();
    std::vector<uint32_t> cached(n), remap(vc);
    meshopt_optimizeVertexCache(cached.data(), m.indices().data(), n, vc);
    const size_t unique = meshopt_optimizeVertexFetchRemap(remap.data(), cached.data(), n, vc);
    s.indices.resize(n);
    meshopt_remapIndexBuffer(s.indices.data(), cached.data(), n, remap.data());
    s.codes.resize(unique * 3);
    meshopt_remapVertexBuffer(s.codes.data(), m.position_codes().data(), vc, 6, remap.data());
    if (m.has_normals()) {
        s.oct.resize(unique * 2);
        meshopt_remapVertexBuffer(s.oct.data(), m.normal_codes().data(), vc, 2, remap.data());
    }
    return s;
}

void print_cache(const char* what, std::span<const uint32_t> idx, size_t vertices) {
    const auto c = meshopt_analyzeVertexCache(idx.data(), idx.size(), vertices, 16, 0, 0);
    const auto f = meshopt_analyzeVertexFetch(idx.data(), idx.size(), vertices, 8);
    std::printf("  %-32s ACMR %.3f  ATVR %.3f  fetch overfetch %.2f\n", what, c.acmr, c.atvr, f.overfetch);
}

// A static mesh of codes in the box of `box`'s positions (the kiosk's formats).
render::MeshData codes_mesh(const pm::ProgressiveMesh& box, std::span<const uint32_t> indices,
                            std::span<const uint16_t> codes, std::span<const uint8_t> oct) {
    render::MeshData data;
    data.indices = indices;
    data.position_codes = codes;
    data.normal_codes = oct;
    data.has_position_box = true;
    data.position_box_min = box.bounds_min();
    data.position_box_max = box.bounds_max();
    data.vertex_count = codes.size() / 3;
    return data;
}

// The cache figures of each order of one level: the kiosk's prefix, what it
// drew once the level settled (ordered), the file's order, the static mesh.
void print_orders(const render::Renderer& renderer, render::ModelId id, bool ordered, const pm::ProgressiveMesh& m,
                  const pm::ProgressiveMesh& p, const StaticLevel& s) {
    const size_t n = m.triangle_count() * 3;
    print_cache("bpm, batched order (kiosk's prefix)", m.indices().first(n), m.vertex_count());
    if (!ordered || !renderer.read_ordered_indices(id, [&](std::span<const uint32_t> idx) {
            print_cache("bpm, settled level (kiosk, drawn)", idx, m.vertex_count());
        }))
        std::printf("  the level was not drawn from an ordered copy: the prefix was timed\n");
    print_cache("bpm, refinement order (file)", p.indices().first(n), p.vertex_count());
    print_cache("static, meshoptimizer", s.indices, s.codes.size() / 3);
}

}  // namespace

bool settle_level(render::Renderer& r, render::ModelId id, const render::View& camera,
                  const render::FrameOptions& frame, double seconds, double* order_ms) {
    const auto start = std::chrono::steady_clock::now();
    if (!r.orders_level(id)) return false;
    while (!r.level_ordered(id)) {
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds) return false;
        (void)frame_ms(r, camera, frame);
        if (order_ms) *order_ms = std::max(*order_ms, r.last_frame_stats().level_order_ms);
        r.finish_level_orders();
    }
    return true;
}

Status compare_with_static(render::Renderer& renderer, render::ModelId id, ModelSource& source,
                           const std::string& bpm_path, const render::View& camera, const render::FrameOptions& frame,
                           int min_pairs, double seconds) {
    auto batched = pm::read_bpm(bpm_path);
    if (!batched) return batched.error();
    auto plain = pm::read_bpm(bpm_path, pm::BpmStream::FaceOrder::Refinement);
    if (!plain) return plain.error();
    // The structure the benchmark drew: the largest, as there.
    const auto largest = [](auto& v) {
        return std::max_element(
                   v.begin(), v.end(),
                   [](const auto& a, const auto& b) { return a->max_triangle_count() < b->max_triangle_count(); })
            ->get();
    };
    pm::ProgressiveMesh& m = *largest(*batched);
    pm::ProgressiveMesh& p = *largest(*plain);
    std::printf(
        "draw order (baseline shader, wall ms on this GL_RENDERER): the .bpm level as the kiosk draws it vs the same "
        "triangles as a static mesh meshoptimizer ordered (vertex cache + fetch); ratio: median over pairs of bpm "
        "frame / mean of the static frames around it (goal <= 1.15); refine_ms, refine_x: the file's refinement order "
        "(the kiosk's before batching) uploaded as a static mesh, likewise; gpu_bpm, gpu_static, gpu_ratio: the same "
        "in GPU time (GL_EXT_disjoint_timer_query, '-' without it); goal judged on both: on a GPU the wall time also "
        "holds the submission and the glFinish round trip, a software rasterizer's timer may see only part of its "
        "work\n");
    std::printf("%-5s %-9s %9s %9s %6s %9s %8s %8s %10s %9s %5s %s\n", "LOD", "triangles", "bpm_ms", "static_ms",
                "ratio", "refine_ms", "refine_x", "gpu_bpm", "gpu_static", "gpu_ratio", "pairs", "goal");
    GpuTimer timer;
    for (double lod : {1.0, 0.4, 0.1}) {
        source.set_lod(lod);
        if (const render::Dirty d = source.take_dirty(); d.vertex_begin < d.vertex_end || d.index_begin < d.index_end) {
            if (auto s = renderer.update_model(id, source.upload_mesh(), d); !s) return s;
            source.release_arrays();
        }
        m.set_level(m.level_for_triangles(source.triangles()));
        p.set_level(m.level());
        if (m.triangle_count() != source.triangles())
            return input_error(bpm_path + ": the benchmark's level does not match a second read of the file");
        const StaticLevel s = optimise(m);
        // The file's refinement order as a static mesh (the kiosk's order before batching).
        const render::MeshData plain_data =
            codes_mesh(p, p.indices().first(p.triangle_count() * 3), p.position_codes().first(p.vertex_count() * 3),
                       p.normal_codes().first(p.has_normals() ? p.vertex_count() * 2 : 0));
        auto sid = renderer.add_model(codes_mesh(m, s.indices, s.codes, s.oct), "static level");
        if (!sid) return sid.error();
        auto pid = renderer.add_model(plain_data, "refinement order");
        if (!pid) return pid.error();
        for (render::ModelId other : {sid.value(), pid.value()}) {
            *renderer.state(other) = *renderer.state(id);
            renderer.state(other)->morph_begin = SIZE_MAX;  // drawn as they are
            renderer.state(other)->morph = 1.0f;
        }
        // Frames cycle static, bpm, refinement; each of the others is divided by
        // the mean of the static frames around it.
        const render::ModelId models[3] = {sid.value(), id, pid.value()};
        std::vector<double> gpu_stat, gpu_bpm, gpu_ratio;  // NaN entries: no timer or a disjoint event
        double order_ms = 0.0;                             // the largest FrameStats::level_order_ms
        const auto draw = [&](int which) {
            for (int k = 0; k < 3; ++k) renderer.state(models[k])->visible = k == which;
            timer.begin();
            const double wall = frame_ms(renderer, camera, frame);
            timer.end();
            order_ms = std::max(order_ms, renderer.last_frame_stats().level_order_ms);
            const double gpu = timer.milliseconds();
            if (which == 0) gpu_stat.push_back(gpu);
            if (which == 1) gpu_bpm.push_back(gpu);
            return wall;
        };
        for (int i = 0; i < 2; ++i)
            for (int k = 0; k < 3; ++k) (void)draw(k);
        // The level stays: the kiosk draws it from its ordered copy once that is made.
        for (int k = 0; k < 3; ++k) renderer.state(models[k])->visible = k == 1;
        const bool ordered = settle_level(renderer, id, camera, frame, 30.0, &order_ms);
        gpu_stat.clear();
        gpu_bpm.clear();
        std::vector<double> stat{draw(0)}, bpm, plain_ms, ratio, plain_ratio;
        const auto start = std::chrono::steady_clock::now();
        while (bpm.size() < size_t(std::max(min_pairs, 1)) ||
               (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < seconds &&
                bpm.size() < 200)) {
            bpm.push_back(draw(1));
            plain_ms.push_back(draw(2));
            stat.push_back(draw(0));
            const double around = 0.5 * (stat[stat.size() - 2] + stat.back());
            ratio.push_back(bpm.back() / around);
            plain_ratio.push_back(plain_ms.back() / around);
            const double gpu_around = 0.5 * (gpu_stat[gpu_stat.size() - 2] + gpu_stat.back());
            if (std::isfinite(gpu_bpm.back() / gpu_around)) gpu_ratio.push_back(gpu_bpm.back() / gpu_around);
        }
        renderer.state(id)->visible = true;
        renderer.remove_model(sid.value());
        renderer.remove_model(pid.value());
        const double r = median(ratio);
        char gpu[40] = "       -          -         -";
        if (!gpu_ratio.empty()) {
            const auto finite_median = [](std::vector<double> v) {
                v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
                return median(v);
            };
            std::snprintf(gpu, sizeof(gpu), "%8.3f %10.3f %9.2f", finite_median(gpu_bpm), finite_median(gpu_stat),
                          median(gpu_ratio));
        }
        const char* gpu_verdict = gpu_ratio.empty() ? "" : median(gpu_ratio) <= 1.15 ? ", gpu ok" : ", gpu MISSED";
        std::printf("%3.0f%%  %-9zu %9.2f %9.2f %6.2f %9.2f %8.2f %s %5zu <= 1.15x wall %s%s\n", lod * 100,
                    m.triangle_count(), median(bpm), median(stat), r, median(plain_ms), median(plain_ratio), gpu,
                    ratio.size(), r <= 1.15 ? "ok" : "MISSED", gpu_verdict);
        std::printf(
            "  ordering the settled level cost the render thread %.2f ms in its slowest frame (read-back or "
            "upload; meshoptimizer on a worker)\n",
            order_ms);
        print_orders(renderer, id, ordered, m, p, s);
        std::fflush(stdout);
    }
    return ok_status();
}

}  // namespace body::kiosk
