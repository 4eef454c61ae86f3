#pragma once
// RGBA8 images for screenshots and the render tests: PNG output through
// stb_image_write (written atomically), PNG input through stb_image, and a box
// downsample for supersampled screenshots.
#include <cstdint>
#include <string>
#include <vector>

#include "shared/error.h"

namespace body::render {

struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgba;  // top row first, 4 bytes per pixel
    const uint8_t* at(int x, int y) const {
        return rgba.data() + (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)) * 4;
    }
};

// Writes RGB (alpha dropped: frames are opaque) as PNG, atomically.
Status write_png(const std::string& path, const Image& image);
Result<Image> read_png(const std::string& path);
// Averages factor x factor blocks (factor >= 1 dividing both sizes).
Image downsample(const Image& image, int factor);

}  // namespace body::render
