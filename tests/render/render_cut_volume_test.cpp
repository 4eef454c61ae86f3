// The bundle's grey-level volume on the cut plane's caps (scene.json
// cut_plane.volume): the file format's checks, and on llvmpipe the cap of a
// cube cut through a gradient volume showing the gradient's grey at known
// pixels, mixed with the cap colour; no volume (or a mix of 0) leaves the
// cap exactly as it was.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "shared/scene/slice_volume.h"
#include "tests/render/render_fixture.h"
#include "tests/render/render_golden.h"

using namespace body;
using namespace body::render;
using body::test::RenderFixture;

namespace {

// 16 x 4 x 4 voxels over the cube [-1, 1]^3, grey 17 * i along x: the grey
// at world x is 136 * (x + 0.9375) between the first and last voxel centres.
SliceVolume gradient_volume() {
    SliceVolume v;
    v.dims = {16, 4, 4};
    v.affine = {0.125f, 0, 0, -0.9375f, 0, 0.5f, 0, -0.75f, 0, 0, 0.5f, -0.75f};
    for (uint32_t k = 0; k < 4; ++k)
        for (uint32_t j = 0; j < 4; ++j)
            for (uint32_t i = 0; i < 16; ++i) v.voxels.push_back(static_cast<uint8_t>(17 * i));
    return v;
}

using test::expect_golden;
using test::pixel_of;

}  // namespace

TEST(SliceVolumeFile, RoundTripsAndNamesTheBadByte) {
    const SliceVolume v = gradient_volume();
    const std::vector<uint8_t> bytes = slice_volume_bytes(v);
    ASSERT_EQ(bytes.size(), 68u + 256u);
    auto back = parse_slice_volume(bytes, "g.vol");
    ASSERT_TRUE(back.ok()) << back.error().message;
    EXPECT_EQ(back->dims, v.dims);
    EXPECT_EQ(back->affine, v.affine);
    EXPECT_EQ(back->voxels, v.voxels);
    auto bad = [&](std::vector<uint8_t> b) {
        auto r = parse_slice_volume(b, "g.vol");
        return r.ok() ? std::string() : r.error().message;
    };
    std::vector<uint8_t> b = bytes;
    b[3] = 'X';
    EXPECT_EQ(bad(b), "g.vol: byte 0: not a grey-level volume (magic BODYVOL1)");
    b = bytes;
    b[12] = 0;  // ny = 0
    EXPECT_EQ(bad(b), "g.vol: byte 12: dimension 0 is outside 1..1024");
    b = bytes;
    b.pop_back();
    EXPECT_EQ(bad(b), "g.vol: byte 68: 255 bytes of voxels, the dims need 256");
    b = bytes;
    std::fill(b.begin() + 20, b.begin() + 68, 0);  // a zero affine
    EXPECT_EQ(bad(b), "g.vol: byte 20: singular voxel-to-scene affine");
    EXPECT_EQ(bad(std::vector<uint8_t>(bytes.begin(), bytes.begin() + 30)),
              "g.vol: byte 30: file ends inside the header");
}

// A cube cut at z = 0 seen straight on: the cap is the square [-1, 1]^2 and
// its pixels carry the gradient's grey (70%) over the red cap colour (30%).
TEST(CutVolume, CapShowsTheGreyLevelAtItsWorldPosition) {
    constexpr int kW = 320, kH = 200;
    RenderFixture f(kW, kH);
    if (!f.ok()) GTEST_SKIP() << "no headless EGL/GLES 3: " << f.why();
    static const test::GenMesh box = test::cube(1.0f);
    Renderer& r = f.renderer();
    auto id = r.add_model(box.data(), "box");
    ASSERT_TRUE(id.ok());
    r.state(id.value())->color = {0.3f, 0.6f, 0.9f};
    const View view = View::framing(Vec3f(0.0f), 1.8f, Vec3f(0.0f, 0.0f, 1.0f));
    FrameOptions o = f.frame();
    o.cut.enabled = true;
    o.cut.plane = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
    o.cut.cap_color = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
    const Image plain = f.draw(view, {}, o);

    const SliceVolume v = gradient_volume();
    ASSERT_TRUE(r.set_cut_volume(&v).ok());
    EXPECT_GE(r.gpu_bytes(), 256u);
    const Image grey = f.draw(view, {}, o);
    for (float x : {-0.8f, -0.5f, -0.2f, 0.0f, 0.3f, 0.6f, 0.85f}) {
        const auto [col, row] = pixel_of(view, Vec3f(x, 0.3f, 0.0f), kW, kH);
        const uint8_t* p = grey.at(col, row);
        const float g = 136.0f * (x + 0.9375f);
        EXPECT_NEAR(p[1], 0.7f * g, 4.0f) << "x " << x;
        EXPECT_NEAR(p[2], 0.7f * g, 4.0f) << "x " << x;
        EXPECT_NEAR(p[0], 76.5f + 0.7f * g, 4.0f) << "x " << x;
        const uint8_t* q = plain.at(col, row);
        EXPECT_EQ(q[0], 255);
        EXPECT_EQ(q[1], 0);
    }
    expect_golden("cut_volume", grey);
    // A mix of 0 and a removed volume give the plain cap, byte for byte.
    o.cut.volume_mix = 0.0f;
    EXPECT_EQ(f.draw(view, {}, o).rgba, plain.rgba);
    o.cut.volume_mix = 0.7f;
    ASSERT_TRUE(r.set_cut_volume(nullptr).ok());
    EXPECT_EQ(f.draw(view, {}, o).rgba, plain.rgba);
}

// CutPlane::volume_around: the slice image on the plane around the cap as
// well, within the volume's box. A half-size cube cut at z = 0 inside the
// gradient volume [-1, 1]^3, a small cube behind the plane inside the box
// (hidden by the image) and one beside the box (still seen).
TEST(CutVolume, AroundTheCapTheImageFillsThePlaneWithinTheVolume) {
    constexpr int kW = 320, kH = 200;
    RenderFixture f(kW, kH);
    REQUIRE_GL(f);
    static const test::GenMesh box = test::cube(1.0f);
    Renderer& r = f.renderer();
    auto add = [&](Vec3f at, float half, Vec3f colour) {
        auto id = r.add_model(box.data(), "box");
        EXPECT_TRUE(id.ok());
        ModelState* st = r.state(id.value());
        st->color = colour;
        st->transform = glm::translate(glm::mat4(1.0f), at) * glm::scale(glm::mat4(1.0f), Vec3f(half));
    };
    add(Vec3f(0.0f), 0.5f, {0.3f, 0.6f, 0.9f});
    add(Vec3f(-0.7f, 0.6f, -0.6f), 0.15f, {0.1f, 0.8f, 0.1f});  // behind the plane, inside the box
    add(Vec3f(1.5f, 0.0f, -0.5f), 0.2f, {0.1f, 0.8f, 0.1f});    // behind the plane, beside the box
    const View view = View::framing(Vec3f(0.0f), 2.0f, Vec3f(0.0f, 0.0f, 1.0f));
    FrameOptions o = f.frame();
    o.cut.enabled = true;
    o.cut.plane = glm::vec4(0.0f, 0.0f, 1.0f, 0.0f);
    o.cut.cap_color = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
    const SliceVolume v = gradient_volume();
    ASSERT_TRUE(r.set_cut_volume(&v).ok());
    const Image caps = f.draw(view, {}, o);
    o.cut.volume_around = true;
    const Image around = f.draw(view, {}, o);
    auto at = [&](const Image& img, Vec3f p) {
        const auto [col, row] = pixel_of(view, p, kW, kH);
        return img.at(col, row);
    };
    auto grey = [](float x) { return 136.0f * (x + 0.9375f); };
    // On the cap: as before, the grey mixed with the cap colour.
    for (const Image* img : {&caps, &around}) {
        EXPECT_NEAR(at(*img, {0.2f, 0.2f, 0.0f})[0], 76.5f + 0.7f * grey(0.2f), 4.0f);
        EXPECT_NEAR(at(*img, {0.2f, 0.2f, 0.0f})[1], 0.7f * grey(0.2f), 4.0f);
    }
    // Around the cap, inside the box: the grey level alone; without the option the background.
    for (const Vec3f p : {Vec3f(0.8f, -0.8f, 0.0f), Vec3f(-0.8f, -0.3f, 0.0f), Vec3f(0.3f, 0.8f, 0.0f)}) {
        const uint8_t* q = at(around, p);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(q[c], grey(p.x), 4.0f) << "x " << p.x << " channel " << c;
        EXPECT_EQ(std::vector<uint8_t>(at(caps, p), at(caps, p) + 3),
                  std::vector<uint8_t>(caps.rgba.begin(), caps.rgba.begin() + 3));
    }
    // The small cube behind the plane inside the box is hidden; the one beside the box is not.
    const uint8_t* hidden_before = at(caps, {-0.7f, 0.6f, -0.45f});
    EXPECT_GT(hidden_before[1], hidden_before[0] + 60);  // green
    const uint8_t* hidden = at(around, {-0.7f, 0.6f, -0.45f});
    const Vec3f eye = view.eye, on_plane = eye + (Vec3f(-0.7f, 0.6f, -0.45f) - eye) * (eye.z / (eye.z + 0.45f));
    EXPECT_NEAR(hidden[0], grey(on_plane.x), 4.0f);  // the image where the eye's ray crosses the plane
    EXPECT_NEAR(hidden[1], grey(on_plane.x), 4.0f);
    const uint8_t* beside = at(around, {1.5f, 0.0f, -0.3f});
    EXPECT_GT(beside[1], beside[0] + 60);
    // Outside the box the plane shows nothing.
    const uint8_t* outside = at(around, {1.25f, 0.8f, 0.0f});
    EXPECT_EQ(std::vector<uint8_t>(outside, outside + 3),
              std::vector<uint8_t>(caps.rgba.begin(), caps.rgba.begin() + 3));
    expect_golden("cut_volume_around", around);
    ASSERT_TRUE(r.set_cut_volume(nullptr).ok());
    EXPECT_EQ(f.draw(view, {}, o).rgba, f.draw(view, {},
                                               [&] {
                                                   FrameOptions p = o;
                                                   p.cut.volume_around = false;
                                                   return p;
                                               }())
                                            .rgba);  // without a volume the option draws nothing
}
