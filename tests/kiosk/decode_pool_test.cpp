// The shared decoding threads: every base before any detail, larger priority
// first, detail only once released; and a scene of many files never runs more
// threads than the pool has.
#include "kiosk/scene/decode_pool.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>
#include <thread>

#include "builder/lod/bpm_writer.h"
#include "kiosk/scene/scene_models.h"
#include "kiosk/scene/stream_loader.h"
#include "tests/common/test_meshes.h"

namespace body::kiosk {
namespace {

// A task of `bases` steps to its base meshes and `detail` steps after, logging each step.
struct LoggedTask final : DecodeTask {
    LoggedTask(char name, int bases, int detail, std::vector<std::string>& log, std::mutex& log_mutex)
        : name(name), bases(bases), detail(detail), log(log), log_mutex(log_mutex) {}
    DecodeNeed step(std::vector<uint8_t>&) override {
        if (gate) gate->wait();
        std::lock_guard guard(log_mutex);
        const bool in_bases = bases > 0;
        log.push_back(std::string{name, in_bases ? 'b' : 'd'});
        if (in_bases) return --bases > 0 ? DecodeNeed::Bases : detail > 0 ? DecodeNeed::Detail : DecodeNeed::Done;
        return --detail > 0 ? DecodeNeed::Detail : DecodeNeed::Done;
    }
    char name;
    int bases, detail;
    std::vector<std::string>& log;
    std::mutex& log_mutex;
    std::shared_future<void>* gate = nullptr;
};

TEST(DecodePool, StepsEveryBaseBeforeAnyDetailLargerFirstAndDetailOnlyWhenReleased) {
    std::vector<std::string> log;
    std::mutex log_mutex;
    std::promise<void> open;
    std::shared_future<void> gate = open.get_future().share();
    LoggedTask first('a', 1, 1, log, log_mutex), small('s', 2, 2, log, log_mutex), large('l', 1, 2, log, log_mutex),
        held('h', 1, 1, log, log_mutex);
    first.gate = &gate;  // the one thread waits in a's first step until every task is queued
    {
        DecodePool pool(1);
        pool.add(&first, 5.0);
        pool.add(&small, 1.0);
        pool.add(&large, 3.0);
        pool.add(&held, 2.0);
        pool.release(&first);
        pool.release(&small);
        pool.release(&large);
        open.set_value();
        for (int i = 0; i < 5000; ++i) {  // up to 10 s on a loaded machine
            {
                std::lock_guard guard(log_mutex);
                if (log.size() >= 10) break;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));  // h's detail must not come
        pool.remove(&first);
        pool.remove(&small);
        pool.remove(&large);
        pool.remove(&held);
    }
    // Bases: a (it was first), then l, h, s by priority; detail of the released
    // ones by priority; h's detail never (not released).
    EXPECT_EQ(log, (std::vector<std::string>{"ab", "lb", "hb", "sb", "sb", "ad", "ld", "ld", "sd", "sd"}));
}

int threads_alive() {
    int n = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator("/proc/self/task")) ++n;
    return n;
}

// The hostile-input case: a bundle of many models (here 1,000 references to one
// small file) queues them on the pool instead of starting a thread each.
TEST(DecodePool, AThousandModelSceneRunsOnThePoolsThreadsOnly) {
    auto bytes = lod::encode_bpm(std::vector<Mesh>{test::uv_sphere(8, 16)}, lod::LodOptions{});
    ASSERT_TRUE(bytes) << bytes.error().message;
    char name[] = "/tmp/body_pool_XXXXXX.bpm";
    const int fd = ::mkstemps(name, 4);
    ASSERT_GE(fd, 0);
    ::close(fd);
    std::ofstream(name, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes->data()), static_cast<std::streamsize>(bytes->size()));
    scene::Scene scene;
    for (int i = 0; i < 1000; ++i) {
        scene::Model m;
        m.name = std::to_string(i);  // unique names
        m.file = m.path = name;
        scene.models.push_back(m);
    }
    const int before = threads_alive();
    int most = before;
    {
        SceneModels models(scene);
        // Sampled while the bases and then the detail decode.
        for (int i = 0; i < 20; ++i) most = std::max(most, threads_alive());
        models.release_detail(false);
        for (int i = 0; i < 20; ++i) most = std::max(most, threads_alive());
        models.release_detail(true);  // returns once every file is decoded
    }
    EXPECT_LE(most, before + static_cast<int>(DecodePool::shared().threads()));
    EXPECT_GE(DecodePool::shared().threads(), 1u);
    ::unlink(name);
}

}  // namespace
}  // namespace body::kiosk
