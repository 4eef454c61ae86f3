// Tiling speed: a pair of contours of n = 1k, 10k, 100k vertices each
// (smooth, shifted and twisted against each other), both methods, against a
// baseline from the same run (one linear pass over the points: the perimeter
// of both contours). Prints contour vertices tiled per second, the slowdown
// against the baseline per vertex, and the growth when n grows tenfold (10x
// is linear, ~13x is n log n, 100x is quadratic).
// The optimal method is O(n^2 log n) time and O(n^2) bits of memory, so it
// runs at 1k and 10k only.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "builder/tiling/tiling.h"

namespace {

using body::Vec3;

std::vector<Vec3> contour(size_t n, double z, double shift, double twist, double wobble) {
    std::vector<Vec3> c(n);
    for (size_t k = 0; k < n; ++k) {
        double t = twist + 2 * M_PI * double(k) / double(n);
        double r = 10 + wobble * std::cos(5 * t) + 0.5 * std::sin(13 * t);
        c[k] = {shift + 1.3 * r * std::cos(t), r * std::sin(t), z};
    }
    return c;
}

struct Pair {
    std::vector<Vec3> lower, upper;
};

const Pair& pair_of(size_t n) {
    static std::map<size_t, Pair> cache;
    auto it = cache.find(n);
    if (it == cache.end())
        it = cache.emplace(n, Pair{contour(n, 0, 0, 0, 1.5), contour(n - n / 7, 1.5, 0.8, 0.4, 2.0)}).first;
    return it->second;
}

void BM_Baseline_Perimeter(benchmark::State& state) {
    const Pair& p = pair_of(size_t(state.range(0)));
    for (auto _ : state) {
        double sum = 0;
        for (const auto* c : {&p.lower, &p.upper})
            for (size_t k = 0; k < c->size(); ++k) sum += glm::length((*c)[(k + 1) % c->size()] - (*c)[k]);
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(int64_t(state.iterations() * (p.lower.size() + p.upper.size())));
}

void tile(benchmark::State& state, body::TilingMethod method) {
    const Pair& p = pair_of(size_t(state.range(0)));
    std::vector<uint32_t> tris;
    for (auto _ : state) {
        auto s = body::tile_band(p.lower, p.upper, method, tris);
        if (!s) state.SkipWithError(s.error().message.c_str());
        benchmark::DoNotOptimize(tris.data());
    }
    state.SetItemsProcessed(int64_t(state.iterations() * (p.lower.size() + p.upper.size())));
}

void BM_TileMultires(benchmark::State& state) { tile(state, body::TilingMethod::Multires); }
void BM_TileOptimal(benchmark::State& state) { tile(state, body::TilingMethod::Optimal); }

BENCHMARK(BM_Baseline_Perimeter)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(BM_TileMultires)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TileOptimal)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->Iterations(1);

// Collects the runs to print the summary after the normal console output.
class SummaryReporter : public benchmark::ConsoleReporter {
public:
    std::map<std::string, std::map<long, double>> seconds_per_vertex;  // name -> n -> s

    void ReportRuns(const std::vector<Run>& runs) override {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& r : runs) {
            if (r.error_occurred || r.run_type != Run::RT_Iteration) continue;
            std::string name = r.run_name.function_name;
            long n = std::stol(r.run_name.args);
            double per_iter = r.cpu_accumulated_time / double(r.iterations);  // CPU: the machine may be shared
            double vertices = double(n + (n - n / 7));
            seconds_per_vertex[name][n] = per_iter / vertices;
        }
    }

    void summary() const {
        auto base = seconds_per_vertex.find("BM_Baseline_Perimeter");
        std::printf("\nsummary (CPU time; pair of n and n - n/7 vertices; growth = time(10n) / time(n))\n");
        std::printf("%-18s %8s %16s %18s %8s\n", "method", "n", "vertices/s", "x baseline/vertex", "growth");
        for (const auto& [name, by_n] : seconds_per_vertex) {
            double prev_time = 0;
            long prev_n = 0;
            for (const auto& [n, spv] : by_n) {
                double vertices = double(n + (n - n / 7));
                double ratio = base != seconds_per_vertex.end() && base->second.count(n) ? spv / base->second.at(n) : 0;
                double time = spv * vertices;
                std::string growth = prev_n ? std::to_string(time / prev_time).substr(0, 6) : "-";
                std::printf("%-18s %8ld %16.0f %18.1f %8s\n", name.c_str(), n, 1.0 / spv, ratio, growth.c_str());
                prev_time = time;
                prev_n = n;
            }
        }
    }
};

}  // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    SummaryReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    reporter.summary();
    benchmark::Shutdown();
    return 0;
}
