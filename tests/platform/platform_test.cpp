// Backend names and parsing, sizes, and the failure of backends without devices.
#include "platform/platform.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

using namespace body::platform;

TEST(Platform, BackendNamesRoundTrip) {
    for (Backend b : {Backend::Auto, Backend::Headless, Backend::Glfw, Backend::Drm}) {
        auto parsed = parse_backend(backend_name(b));
        ASSERT_TRUE(parsed.ok());
        EXPECT_EQ(parsed.value(), b);
    }
    auto bad = parse_backend("wayland");
    ASSERT_FALSE(bad.ok());
    EXPECT_EQ(bad.error().exit_code, body::kExitBadInput);
    EXPECT_NE(bad.error().message.find("wayland"), std::string::npos);
}

TEST(Platform, HeadlessIsAlwaysCompiledAndLast) {
    auto list = compiled_backends();
    ASSERT_FALSE(list.empty());
    EXPECT_EQ(list.back(), Backend::Headless);
    EXPECT_EQ(std::count(list.begin(), list.end(), Backend::Auto), 0);
}

TEST(Platform, ParsesSizes) {
    auto s = parse_size("1280x800");
    ASSERT_TRUE(s.ok());
    EXPECT_EQ(s->first, 1280);
    EXPECT_EQ(s->second, 800);
    for (const char* bad : {"", "1280", "1280x", "0x800", "1280x800x3", "-1x5", "99999x10"})
        EXPECT_FALSE(parse_size(bad).ok()) << bad;
}

#ifdef BODY_WITH_DRM
// The error --platform drm gives with `o` (which must fail on these machines).
body::Error drm_failure(SurfaceOptions o) {
    o.backend = Backend::Drm;
    auto s = create_surface(o);
    if (s.ok()) {
        ADD_FAILURE() << "a DRM surface opened";
        return body::Error{};
    }
    return s.error();
}

TEST(Platform, DrmWithoutADeviceFailsWithOneLine) {
    SurfaceOptions o;
    o.drm_device = "/nonexistent/dri/card9";
    const body::Error e = drm_failure(o);
    EXPECT_EQ(e.message.find('\n'), std::string::npos);
    EXPECT_NE(e.message.find("drm"), std::string::npos);
    EXPECT_NE(e.message.find("card9"), std::string::npos);
}

TEST(Platform, DrmBadModeIsAUsageError) {
    SurfaceOptions o;
    o.mode = "huge";
    EXPECT_EQ(drm_failure(o).exit_code, body::kExitBadInput);
}
#endif
