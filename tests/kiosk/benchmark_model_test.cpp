// The size of the benchmark's generated model: the subdivision count nearest
// the asked-for triangles (the "~1M-triangle model" on every machine,
// with or without the bunny installed).
#include <gtest/gtest.h>

#include "kiosk/modes/benchmark.h"

namespace body::kiosk {
namespace {

TEST(BenchmarkModel, SubdivisionsGiveTheCountNearestTheTargetByRatio) {
    // The bunny: 278,664 is 3.6x short of a million, 1,114,656 1.11x over.
    EXPECT_EQ(subdivisions_toward(69666, 1000000), 2);
    // The icosphere stand-in: 327,680 is 3.05x short, 1,310,720 1.31x over
    // (it used to stop short, at a third of the target).
    EXPECT_EQ(subdivisions_toward(20, 1000000), 8);
    EXPECT_EQ(subdivisions_toward(1000, 4000), 1);
    EXPECT_EQ(subdivisions_toward(1000, 1000), 0);
    EXPECT_EQ(subdivisions_toward(1000, 100), 0);   // already larger: left as it is
    EXPECT_EQ(subdivisions_toward(1000, 1999), 0);  // 4000 is further off by ratio than 1000
    EXPECT_EQ(subdivisions_toward(1000, 2001), 1);
    EXPECT_EQ(subdivisions_toward(0, 1000), 0);
}

}  // namespace
}  // namespace body::kiosk
