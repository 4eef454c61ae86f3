#include "tests/render/render_fixture.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace body::test {

GenMesh icosphere(int subdivisions, float radius) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    GenMesh m;
    m.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    m.indices = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2,  10, 7, 6, 7, 1, 8,
                 3, 9,  4, 3, 4, 2, 3, 2, 6, 3, 6, 8,  3, 8,  9,  4, 9, 5, 2, 4,  11, 6,  2,  10, 8,  6, 7, 9, 8, 1};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<uint64_t, uint32_t> mid;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            uint64_t key = (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
            auto [it, inserted] = mid.emplace(key, static_cast<uint32_t>(m.positions.size()));
            if (inserted) m.positions.push_back((m.positions[a] + m.positions[b]) * 0.5f);
            return it->second;
        };
        std::vector<uint32_t> out;
        for (size_t f = 0; f < m.indices.size(); f += 3) {
            uint32_t a = m.indices[f], b = m.indices[f + 1], c = m.indices[f + 2];
            uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            out.insert(out.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
        }
        m.indices = std::move(out);
    }
    for (auto& p : m.positions) p = glm::normalize(p) * radius;
    return m;
}

GenMesh cube(float h) {
    GenMesh m;
    for (int i = 0; i < 8; ++i) m.positions.emplace_back(i & 1 ? h : -h, i & 2 ? h : -h, i & 4 ? h : -h);
    m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return m;
}

GenMesh torus(int rings, int segments, float major, float minor) {
    GenMesh m;
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            float u = 2.0f * std::numbers::pi_v<float> * static_cast<float>(r) / static_cast<float>(rings);
            float v = 2.0f * std::numbers::pi_v<float> * static_cast<float>(s) / static_cast<float>(segments);
            float w = major + minor * std::cos(v);
            m.positions.emplace_back(w * std::cos(u), minor * std::sin(v), w * std::sin(u));
        }
    auto at = [&](int r, int s) {
        return static_cast<uint32_t>(((r + rings) % rings) * segments + (s + segments) % segments);
    };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            uint32_t a = at(r, s), b = at(r + 1, s), c = at(r + 1, s + 1), d = at(r, s + 1);
            m.indices.insert(m.indices.end(), {a, d, c, a, c, b});
        }
    return m;
}

RenderFixture::RenderFixture(int width, int height, const render::RendererOptions& options) {
    platform::SurfaceOptions o;
    o.backend = platform::Backend::Headless;
    o.width = width;
    o.height = height;
    auto s = platform::create_surface(o);
    if (!s) {
        why_ = s.error().message;
        return;
    }
    surface_ = std::move(s.value());
    if (auto r = renderer_.init(options); !r) {
        why_ = r.error().message;
        return;
    }
    ok_ = true;
}

render::FrameOptions RenderFixture::frame() const {
    render::FrameOptions o;
    o.width = surface_->width();
    o.height = surface_->height();
    o.framebuffer = surface_->framebuffer();
    return o;
}

render::Image RenderFixture::draw(const render::View& camera, const render::Lighting& lighting) {
    return draw(camera, lighting, frame());
}

render::Image RenderFixture::draw(const render::View& camera, const render::Lighting& lighting,
                                  const render::FrameOptions& o) {
    surface_->make_current();  // another fixture may have been current
    renderer_.render(camera, lighting, o);
    render::Image img;
    img.width = o.width;
    img.height = o.height;
    img.rgba = platform::read_pixels_rgba(o.framebuffer, o.width, o.height);
    return img;
}

double luma(const uint8_t* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }

ImageDiff compare(const render::Image& a, const render::Image& b, int block_threshold) {
    ImageDiff d;
    if (a.width != b.width || a.height != b.height) {
        d.bad_block_fraction = 1.0;
        return d;
    }
    render::Image fa = render::downsample(a, 4), fb = render::downsample(b, 4);
    size_t bad = 0, blocks = static_cast<size_t>(fa.width) * static_cast<size_t>(fa.height);
    for (int y = 0; y < fa.height; ++y)
        for (int x = 0; x < fa.width; ++x) {
            int worst = 0;
            for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(fa.at(x, y)[c] - fb.at(x, y)[c]));
            if (worst > block_threshold) ++bad;
        }
    // Mean luminance change over the pixels showing an object in either image
    // (the background colour is the top-left pixel's), so tone shifts are not
    // diluted by empty background.
    double sum = 0;
    size_t n = 0;
    const uint8_t* bg = a.at(0, 0);
    auto is_bg = [&](const uint8_t* p) {
        return std::abs(p[0] - bg[0]) + std::abs(p[1] - bg[1]) + std::abs(p[2] - bg[2]) <= 6;
    };
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (is_bg(a.at(x, y)) && is_bg(b.at(x, y))) continue;
            sum += luma(b.at(x, y)) - luma(a.at(x, y));
            ++n;
        }
    d.bad_block_fraction = static_cast<double>(bad) / static_cast<double>(blocks);
    d.mean_luma_delta = n ? sum / static_cast<double>(n) : 0.0;
    return d;
}

std::vector<bool> foreground_mask(const render::Image& img, Vec3f bg, int threshold) {
    std::vector<bool> mask(static_cast<size_t>(img.width) * static_cast<size_t>(img.height));
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const uint8_t* p = img.at(x, y);
            int worst = 0;
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(p[c] - static_cast<int>(std::lround(bg[c] * 255.0f))));
            mask[static_cast<size_t>(y) * static_cast<size_t>(img.width) + static_cast<size_t>(x)] = worst > threshold;
        }
    return mask;
}

}  // namespace body::test
