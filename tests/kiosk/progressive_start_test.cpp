// The kiosk's loading contract on a scene of many .bpm files (kiosk_run.cpp,
// SceneModels::load_ready / upload_arrived): the first frame is drawn before
// the base meshes are decoded, with the camera and the layout already final
// (every ModelInfo read from the files' INFO sections); the models then arrive
// over the following frames until every one is drawn; and the process's
// threads do not grow with the number of files. No timing: the decoding
// threads are held busy until the first frame is out, so the order is forced.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "builder/lod/bpm_writer.h"
#include "kiosk/app/kiosk_app.h"
#include "kiosk/app/kiosk_run.h"
#include "kiosk/scene/decode_pool.h"
#include "shared/scene/scene.h"
#include "tests/common/headless_surface.h"
#include "tests/common/test_dir.h"
#include "tests/common/test_meshes.h"

namespace body::kiosk {
namespace {

namespace fs = std::filesystem;

// Occupies one pool thread (its priority beats every file's) until opened.
struct Blocker final : DecodeTask {
    std::atomic<bool>& open;
    explicit Blocker(std::atomic<bool>& open) : open(open) {}
    DecodeNeed step(std::vector<uint8_t>&) override {
        while (!open.load()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        return DecodeNeed::Done;
    }
};

size_t process_threads() {
    size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator("/proc/self/task")) ++n;
    return n;
}

TEST(ProgressiveStart, FirstFrameBeforeTheBasesThenEveryModelArrives) {
    const fs::path dir = test::fresh_test_dir("body_progressive_start");
    auto bytes = lod::encode_bpm(std::vector<Mesh>{test::uv_sphere(6, 12)}, lod::LodOptions{});
    ASSERT_TRUE(bytes) << bytes.error().message;
    std::ofstream(dir / "s.bpm", std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.value().data()), std::streamsize(bytes.value().size()));
    // 300 files (copies: each is opened and decoded on its own) on a 15 x 20 grid.
    const int models = 300;
    std::ostringstream json;
    json << "{\"models\": [";
    for (int i = 0; i < models; ++i) {
        std::ostringstream file;
        file << "m" << i << ".bpm";
        fs::copy_file(dir / "s.bpm", dir / file.str());
        json << (i ? "," : "") << "{\"name\": \"m" << i << "\", \"file\": \"" << file.str()
             << "\", \"transform\": {\"translate\": [" << i % 15 * 3 << ", " << i / 15 * 3 << ", 0]}}";
    }
    json << "]}";
    std::ofstream(dir / "scene.json") << json.str();
    auto scene = scene::read_scene((dir / "scene.json").string());
    ASSERT_TRUE(scene) << scene.error().message;
    auto surface = body::test::headless_surface();
    if (!surface) GTEST_SKIP() << "no headless GL: " << surface.error().message;

    DecodePool& pool = DecodePool::shared();
    std::atomic<bool> open{false};
    std::vector<std::unique_ptr<Blocker>> blockers;
    for (size_t t = 0; t < pool.threads(); ++t) {
        blockers.push_back(std::make_unique<Blocker>(open));
        pool.add(blockers.back().get(), 1e30);
    }
    KioskRunOptions o;
    o.frames = 100000;  // stopped by the hook once every model is drawn
    size_t first_pending = 0, first_triangles = 1, last_pending = models, frames = 0, max_threads = 0;
    size_t models_drawn_last = 0;
    bool arrived_in_order = true, infos_final = true;
    o.hooks.frame_done = [&](const FrameReport& f) {
        max_threads = std::max(max_threads, process_threads());
        size_t drawn = 0;
        for (int i = 0; i < f.app->model_count(); ++i) {
            // The layout's bounds are the files' from the start.
            const ModelInfo& mi = f.app->info(i);
            infos_final = infos_final && mi.loaded && mi.full_triangles > mi.base_triangles && mi.radius > 0.5f;
        }
        if (f.frame == 0) {
            first_pending = f.models_pending;
            first_triangles = f.triangles;
            open = true;
        }
        drawn = models - f.models_pending;
        arrived_in_order = arrived_in_order && drawn >= models_drawn_last;
        models_drawn_last = drawn;
        last_pending = f.models_pending;
        frames = size_t(f.frame) + 1;
        return f.models_pending > 0;
    };
    EXPECT_EQ(run_kiosk(*surface.value(), scene.value(), o), 0);
    open = true;
    for (auto& b : blockers) pool.remove(b.get());
    fs::remove_all(dir);
    // The first frame came before any base mesh: every model still to come, nothing drawn.
    EXPECT_EQ(first_pending, size_t(models));
    EXPECT_EQ(first_triangles, 0u);
    EXPECT_TRUE(infos_final);
    // Then all of them, never fewer from one frame to the next, over more than one frame.
    EXPECT_EQ(last_pending, 0u);
    EXPECT_TRUE(arrived_in_order);
    EXPECT_GT(frames, 1u);
    EXPECT_LT(frames, 100000u);
    // A fixed pool, not a thread per file.
    EXPECT_EQ(pool.threads(), std::max<size_t>(1, std::thread::hardware_concurrency() - 1));
    EXPECT_LT(max_threads, size_t(models) / 10);
}

}  // namespace
}  // namespace body::kiosk
