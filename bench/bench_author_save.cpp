// The authoring mode's costs on a real exhibit (default: a 116-model scene like
// the AAL bundle's, `--scene BUNDLE/scene.json` for the real one):
//   read scene      read_scene: the kiosk's own start-up step, the baseline
//   save scene      Document::save: scene_to_json + parse_scene (validation) + atomic write
//   one edit        Document::apply of a colour change (copy, validate, undo step):
//                   what must fit in a frame for "edits apply within one frame"
// The goal (save <= 50 ms for 116 models) is read off the printed times; the
// ratio save / read is printed from the same run.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "kiosk/author/document.h"
#include "shared/scene/scene_write.h"

namespace {

using namespace body;
namespace fs = std::filesystem;

std::string g_scene;
fs::path g_dir;

scene::Scene load() {
    auto s = scene::read_scene(g_scene);
    if (!s) {
        std::fprintf(stderr, "bench_author_save: %s\n", s.error().message.c_str());
        std::exit(2);
    }
    return s.value();
}

// 116 models in 12 groups with two-language labels, as `bodygen exhibit` makes for the AAL atlas.
void write_synthetic(const fs::path& path) {
    scene::Scene s;
    s.kiosk.languages = {"en", "de"};
    for (int g = 0; g < 12; ++g) s.groups.push_back({"group " + std::to_string(g), std::nullopt, std::nullopt, true});
    for (int i = 0; i < 116; ++i) {
        scene::Model m;
        m.name = "region-" + std::to_string(i);
        m.file = "models/region_" + std::to_string(i) + ".bpm";
        m.group = "group " + std::to_string(i % 12);
        m.colour = {0.1f + 0.007f * static_cast<float>(i), 0.5f, 0.9f - 0.005f * static_cast<float>(i)};
        m.labels = {{"en", "Region " + std::to_string(i) + " (left)", "A region of the brain atlas."},
                    {"de", "Region " + std::to_string(i) + " (links)", "Eine Region des Hirnatlas."}};
        s.models.push_back(m);
    }
    if (!scene::save_scene(s, path.string())) std::exit(1);
}

void BM_ReadScene(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(scene::read_scene(g_scene));
}

void BM_SaveScene(benchmark::State& state) {
    kiosk::author::Document doc(load(), g_scene);
    const std::string out = (g_dir / "saved.json").string();
    for (auto _ : state)
        if (!doc.save(out)) state.SkipWithError("save failed");
}

void BM_OneEdit(benchmark::State& state) {
    kiosk::author::Document doc(load(), g_scene);
    float c = 0.0f;
    for (auto _ : state) {
        c = c > 0.9f ? 0.0f : c + 0.01f;
        if (!doc.apply("colour", [&](scene::Scene& s) {
                s.models[0].colour[0] = c;
                return ok_status();
            }))
            state.SkipWithError("edit refused");
    }
}

BENCHMARK(BM_ReadScene)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SaveScene)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_OneEdit)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
    g_dir = fs::temp_directory_path() / ("bench_author_save_" + std::to_string(::getpid()));
    fs::create_directories(g_dir);
    for (int i = 1; i + 1 < argc; ++i)
        if (std::strcmp(argv[i], "--scene") == 0) {
            g_scene = argv[i + 1];
            for (int k = i; k + 2 <= argc; ++k) argv[k] = argv[k + 2];
            argc -= 2;
            break;
        }
    if (g_scene.empty()) {
        g_scene = (g_dir / "scene.json").string();
        write_synthetic(g_scene);
    }
    std::printf("scene: %s (%zu models)\n", g_scene.c_str(), load().models.size());
    benchmark::Initialize(&argc, argv);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    fs::remove_all(g_dir);
    return 0;
}
