// Backend names and parsing, sizes, and the failure of backends without devices.
#include "platform/platform.h"

#include <GLES3/gl3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "platform/egl_context.h"
#include "platform/seat.h"

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

// The headless backend's second choice: a surfaceless GLES 3 context on an EGL
// device. Mesa offers its software device there too, so the path runs on these
// machines; it also passed on NVIDIA's 580 driver (an H200).
TEST(Platform, HeadlessContextOpensOnAnEglDevice) {
    if (!egl_has_extension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), "EGL_EXT_platform_device"))
        GTEST_SKIP() << "this EGL has no device platform";
    auto ctx = EglContext::open_first_device();
    ASSERT_TRUE(ctx.ok()) << ctx.error().message;
    const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    ASSERT_NE(version, nullptr);
    EXPECT_EQ(std::string(version).rfind("OpenGL ES 3", 0), 0u) << version;
    // Drawable without a surface: a framebuffer object clears and reads back.
    GLuint rb = 0, fbo = 0;
    glGenRenderbuffers(1, &rb);
    glBindRenderbuffer(GL_RENDERBUFFER, rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 4, 4);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb);
    ASSERT_EQ(glCheckFramebufferStatus(GL_FRAMEBUFFER), static_cast<GLenum>(GL_FRAMEBUFFER_COMPLETE));
    glClearColor(1.0f, 0.5f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    unsigned char pixel[4] = {};
    glReadPixels(1, 1, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel);
    EXPECT_EQ(pixel[0], 255);
    EXPECT_NEAR(pixel[1], 128, 1);
    EXPECT_EQ(pixel[2], 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &rb);
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

// The seat: the seat manager's when one answers (libseat's builtin one as root),
// else direct opens; either way a device opens, closes and the seat is active.
TEST(Seat, OpensAndClosesADevice) {
    auto seat = Seat::open();
    ASSERT_NE(seat, nullptr);
    seat->dispatch();
    EXPECT_TRUE(seat->active());
    EXPECT_GE(seat->activations(), 1);
    const int fd = seat->open_device("/dev/null");
    if (std::string(seat->kind()) == "direct") {
        ASSERT_GE(fd, 0);
        seat->close_device(fd);
    } else if (fd >= 0) {  // a seat manager may refuse a non-device node
        seat->close_device(fd);
    }
    EXPECT_LT(seat->open_device("/nonexistent/event0"), 0);
}

// The software rasterizer's thread count: 0 (rasterize on the calling thread)
// unless the user chose, and a surface applies it before the driver loads.
TEST(Platform, SoftwareRasterizerRunsOnTheCallingThreadUnlessTheUserChose) {
    const char* before = std::getenv("LP_NUM_THREADS");
    const std::string saved = before ? before : "";
    ::unsetenv("LP_NUM_THREADS");
    EXPECT_EQ(default_software_rasterizer_threads(), "0");
    ::setenv("LP_NUM_THREADS", "3", 1);
    EXPECT_EQ(default_software_rasterizer_threads(), "3");
    ::unsetenv("LP_NUM_THREADS");
    SurfaceOptions options;
    options.backend = Backend::Headless;
    options.width = 16;
    options.height = 16;
    auto surface = create_surface(options);
    ASSERT_NE(std::getenv("LP_NUM_THREADS"), nullptr);
    EXPECT_STREQ(std::getenv("LP_NUM_THREADS"), "0");
    if (before)
        ::setenv("LP_NUM_THREADS", saved.c_str(), 1);
    else
        ::unsetenv("LP_NUM_THREADS");
}
