// Benchmark skeleton: topology analysis of a subdivided sphere, with the
// baseline (one pass over the indices computing the volume) in the same run.
// Prints time per triangle for both; compare the ratio, not the absolute time.
#include <benchmark/benchmark.h>

#include <cmath>

#include "shared/mesh.h"
#include "tests/common/test_meshes.h"

namespace {

using body::test::uv_sphere;

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
