#pragma once
// The headless GL surface the drawing kiosk tests make (each test skips when
// the machine has no headless GL: `if (!s) GTEST_SKIP()`).
#include <memory>

#include "platform/platform.h"
#include "shared/error.h"

namespace body::test {

inline Result<std::unique_ptr<platform::Surface>> headless_surface(int width = 320, int height = 200) {
    platform::SurfaceOptions so;
    so.backend = platform::Backend::Headless;
    so.width = width;
    so.height = height;
    return platform::create_surface(so);
}

}  // namespace body::test
