// The flush pacer's fences (kiosk/render/flush_pacer.h) through a recording
// fake: a fence is deleted only after a newer one was waited for, at most two
// are alive, and release() finishes before it deletes the rest.
#include "kiosk/render/flush_pacer.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace body::render {
namespace {

struct Call {
    char what;  // 'f' fence, 'w' wait, 'r' remove, 'F' finish
    uintptr_t fence;
};
std::vector<Call> g_calls;
uintptr_t g_next = 0;

GLsync as_sync(uintptr_t n) { return reinterpret_cast<GLsync>(n); }
uintptr_t id(GLsync s) { return reinterpret_cast<uintptr_t>(s); }

const SyncCalls kRecording{
    [] {
        g_calls.push_back({'f', ++g_next});
        return as_sync(g_next);
    },
    [](GLsync s) {
        g_calls.push_back({'w', id(s)});
    },
    [](GLsync s) {
        g_calls.push_back({'r', id(s)});
    },
    [] {
        g_calls.push_back({'F', 0});
    },
};

// Checks the contract over the recorded calls; returns the first breach.
std::string breach() {
    uintptr_t newest_waited = 0;
    bool finished = false;
    std::vector<uintptr_t> alive;
    for (const Call& c : g_calls) {
        if (c.what == 'f') alive.push_back(c.fence);
        if (c.what == 'w') newest_waited = std::max(newest_waited, c.fence);
        if (c.what == 'F') finished = true;
        if (c.what == 'r') {
            if (!finished && newest_waited <= c.fence)
                return "fence " + std::to_string(c.fence) + " deleted before a newer one was waited for";
            std::erase(alive, c.fence);
        }
        if (alive.size() > 3) return "more than three fences alive";
    }
    if (!alive.empty()) return std::to_string(alive.size()) + " fences never deleted";
    return "";
}

TEST(FlushPacer, DeletesAFenceOnlyAfterANewerOneWasWaitedFor) {
    for (int flushes : {0, 1, 2, 3, 10, 57}) {
        g_calls.clear();
        g_next = 0;
        {
            FlushPacer pacer(kRecording);
            for (int i = 0; i < flushes; ++i) pacer.flush();
            pacer.release();
        }
        EXPECT_EQ(breach(), "") << flushes << " flushes";
        size_t waits = 0;
        for (const Call& c : g_calls) waits += c.what == 'w';
        EXPECT_EQ(waits, flushes > 0 ? static_cast<size_t>(flushes - 1) : 0u) << flushes << " flushes";
    }
}

TEST(FlushPacer, WaitsForTheSceneBeforeTheLastOne) {
    g_calls.clear();
    g_next = 0;
    FlushPacer pacer(kRecording);
    pacer.flush();
    pacer.flush();
    pacer.flush();
    // The third flush creates fence 3 and waits for fence 2 (fence 1 was waited for by the second).
    ASSERT_GE(g_calls.size(), 2u);
    const Call& last_wait = g_calls[g_calls.size() - 2];
    EXPECT_EQ(last_wait.what, 'w');
    EXPECT_EQ(last_wait.fence, 2u);
    EXPECT_EQ(g_calls.back().what, 'r');
    EXPECT_EQ(g_calls.back().fence, 1u);
    pacer.release();
    EXPECT_EQ(breach(), "");
}

}  // namespace
}  // namespace body::render
