// PrefaultedVector behaves as std::vector whichever path its storage takes: small
// arrays from operator new, large ones from populated or reused mappings; contents
// are value-initialised and survive growth across the threshold.
#include "shared/pm/large_array.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <numeric>
#include <thread>
#include <vector>

namespace body::pm {
namespace {

struct alignas(64) Line {
    double value = 1.5;
    uint32_t tag = 7;
};

TEST(PrefaultedArray, LargeArraysAreZeroedAndWritable) {
    for (const size_t bytes : {kPrefaultMinBytes - 8, kPrefaultMinBytes, size_t(3) << 20, size_t(5) << 20}) {
        PrefaultedVector<uint64_t> v(bytes / 8);
        ASSERT_EQ(v.size(), bytes / 8);
        EXPECT_EQ(std::accumulate(v.begin(), v.end(), uint64_t(0)), 0u) << bytes << " bytes";
        for (size_t i = 0; i < v.size(); ++i) v[i] = i;
        EXPECT_EQ(v.back(), v.size() - 1);
        EXPECT_EQ(reinterpret_cast<uintptr_t>(v.data()) % alignof(uint64_t), 0u);
    }
}

TEST(PrefaultedArray, GrowthAcrossTheThresholdKeepsContents) {
    PrefaultedVector<uint32_t> v;
    for (uint32_t i = 0; i < (3u << 20) / 4; ++i) v.push_back(i * 3u);  // operator new, then mappings
    for (uint32_t i = 0; i < v.size(); i += 4099) ASSERT_EQ(v[i], i * 3u);
    v.resize(10);
    v.shrink_to_fit();
    EXPECT_EQ(v[9], 27u);
}

TEST(PrefaultedArray, OverAlignedElementsKeepTheirAlignmentAndInitialisers) {
    for (const size_t n : {size_t(3), kPrefaultMinBytes / sizeof(Line) + 1}) {
        PrefaultedVector<Line> v(n);
        EXPECT_EQ(reinterpret_cast<uintptr_t>(v.data()) % 64, 0u) << n;
        EXPECT_EQ(v.front().value, 1.5);
        EXPECT_EQ(v.back().tag, 7u);
    }
}

// Freed mappings are kept and handed out again: a reused array must still start
// value-initialised (std::vector's job, the allocator must not defeat it) and arrays
// alive together must never share memory, from any number of threads.
TEST(PrefaultedArray, ReusedMemoryIsNeverSharedBetweenLiveArrays) {
    { PrefaultedVector<uint32_t> first(1 << 20, 7u); }
    PrefaultedVector<uint32_t> again(1 << 20);
    EXPECT_EQ(std::count(again.begin(), again.end(), 0u), ptrdiff_t(again.size()));

    std::vector<std::thread> threads;
    std::atomic<int> mismatches{0};
    for (uint32_t t = 0; t < 4; ++t)
        threads.emplace_back([t, &mismatches] {
            for (uint32_t round = 0; round < 40; ++round) {
                const size_t n = (size_t(64) << 10) + size_t((round * 7919 + t * 104729) % 400000);
                PrefaultedVector<uint32_t> a(n, t * 1000 + round), b(n / 2 + 1, ~(t * 1000 + round));
                for (const uint32_t x : a) mismatches += x != t * 1000 + round;
                for (const uint32_t x : b) mismatches += x != ~(t * 1000 + round);
            }
        });
    for (std::thread& th : threads) th.join();
    EXPECT_EQ(mismatches.load(), 0);
}

}  // namespace
}  // namespace body::pm
