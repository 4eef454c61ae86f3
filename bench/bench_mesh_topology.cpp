// Benchmark skeleton: topology analysis of a subdivided sphere, with the
// baseline (one pass over the indices computing the volume) in the same run.
// Prints time per triangle for both; compare the ratio, not the absolute time.
#include <benchmark/benchmark.h>

#include <cmath>

#include "shared/mesh.h"

namespace {

body::Mesh uv_sphere(int rings, int segments) {
    body::Mesh m;
    m.positions.push_back({0, 0, 1});
    for (int r = 1; r < rings; ++r) {
        double t = M_PI * r / rings;
        for (int s = 0; s < segments; ++s) {
            double p = 2 * M_PI * s / segments;
            m.positions.push_back({std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)});
        }
    }
    m.positions.push_back({0, 0, -1});
    auto ring = [&](int r, int s) { return uint32_t(1 + (r - 1) * segments + (s % segments)); };
    for (int s = 0; s < segments; ++s) m.indices.insert(m.indices.end(), {0, ring(1, s), ring(1, s + 1)});
    for (int r = 1; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s)
            m.indices.insert(m.indices.end(), {ring(r, s), ring(r + 1, s), ring(r + 1, s + 1), ring(r, s),
                                               ring(r + 1, s + 1), ring(r, s + 1)});
    uint32_t south = uint32_t(m.positions.size() - 1);
    for (int s = 0; s < segments; ++s)
        m.indices.insert(m.indices.end(), {south, ring(rings - 1, s + 1), ring(rings - 1, s)});
    return m;
}

void BM_Baseline_Volume(benchmark::State& state) {
    body::Mesh m = uv_sphere(int(state.range(0)), int(state.range(0)) * 2);
    for (auto _ : state) benchmark::DoNotOptimize(body::mesh_volume(m.positions, m.indices));
    state.SetItemsProcessed(int64_t(state.iterations() * m.triangle_count()));
}

void BM_AnalyzeTopology(benchmark::State& state) {
    body::Mesh m = uv_sphere(int(state.range(0)), int(state.range(0)) * 2);
    for (auto _ : state) benchmark::DoNotOptimize(body::analyze_topology(m.positions, m.indices));
    state.SetItemsProcessed(int64_t(state.iterations() * m.triangle_count()));
}

BENCHMARK(BM_Baseline_Volume)->Arg(64)->Arg(256);
BENCHMARK(BM_AnalyzeTopology)->Arg(64)->Arg(256);

}  // namespace

BENCHMARK_MAIN();
