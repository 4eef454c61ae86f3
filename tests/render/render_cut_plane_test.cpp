// The cut plane on llvmpipe (headless EGL): the cap on an input slice equals
// the traced contour to within one pixel at 1280x800 (our meshes pass through
// the input contours), golden pictures of the cut in every style and with
// x-ray, and the properties that make capping right (each cap in its model's
// colour, models on the removed side gone, a model not cut left whole).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "builder/pipeline/build_pipeline.h"
#include "tests/render/render_fixture.h"
#include "tests/render/render_golden.h"

using namespace body;
using namespace body::render;
using body::test::RenderFixture;

namespace {

using test::expect_golden;

// A non-convex blob traced on `slices` planes 1 apart, turning and swelling
// from slice to slice, and a second one beside it on the middle slices (so
// one slice holds two contours of the structure).
ContourStack blob_stack(int slices) {
    ContourStack stack;
    stack.structures.push_back({"blob", "Blob", {0.8, 0.8, 0.8}});
    for (int k = 0; k < slices; ++k) {
        Slice s;
        s.z = static_cast<double>(k);
        Contour c;
        c.structure = "blob";
        const double grow = 1.0 + 0.5 * std::sin(3.14159265 * (k + 0.5) / slices);
        for (int i = 0; i < 72; ++i) {
            const double t = 2.0 * 3.14159265358979 * i / 72.0;
            const double r = 3.0 * grow * (1.0 + 0.3 * std::sin(3.0 * t + 0.4 * k) + 0.1 * std::cos(5.0 * t));
            c.points.push_back({r * std::cos(t), r * std::sin(t)});
        }
        s.contours.push_back(c);
        if (k >= 1 && k + 1 < slices) {
            Contour d;
            d.structure = "blob";
            for (int i = 0; i < 24; ++i) {
                const double t = 2.0 * 3.14159265358979 * i / 24.0;
                d.points.push_back({9.0 + 1.2 * std::cos(t), 1.0 + 0.8 * std::sin(t)});
            }
            s.contours.push_back(d);
        }
        stack.slices.push_back(s);
    }
    return stack;
}

// Pixel centres inside the slice's contours (even-odd), projected with the frame's camera; top row first.
std::vector<bool> contour_mask(const Slice& slice, const View& view, int w, int h) {
    const glm::mat4 pv = view.projection(static_cast<float>(w) / static_cast<float>(h)) * view.view();
    std::vector<std::vector<glm::vec2>> rings;
    for (const Contour& c : slice.contours) {
        auto& ring = rings.emplace_back();
        for (const Vec2& p : c.points) {
            const glm::vec4 clip =
                pv * glm::vec4(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(slice.z), 1.0f);
            ring.emplace_back((clip.x / clip.w + 1.0f) * 0.5f * static_cast<float>(w),
                              (clip.y / clip.w + 1.0f) * 0.5f * static_cast<float>(h));
        }
    }
    std::vector<bool> mask(static_cast<size_t>(w) * static_cast<size_t>(h), false);
    for (int row = 0; row < h; ++row) {
        const float y = static_cast<float>(h - 1 - row) + 0.5f;  // GL window y of the row's centres
        for (int col = 0; col < w; ++col) {
            const float x = static_cast<float>(col) + 0.5f;
            bool inside = false;
            for (const auto& ring : rings)
                for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
                    if ((ring[i].y > y) != (ring[j].y > y) &&
                        x < ring[j].x + (y - ring[j].y) / (ring[i].y - ring[j].y) * (ring[i].x - ring[j].x))
                        inside = !inside;
            mask[static_cast<size_t>(row) * static_cast<size_t>(w) + static_cast<size_t>(col)] = inside;
        }
    }
    return mask;
}

// The mask grown (dilate) or shrunk (erode) by one pixel, 8-neighbourhood.
std::vector<bool> morph(const std::vector<bool>& m, int w, int h, bool dilate) {
    std::vector<bool> out(m.size());
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            bool v = !dilate;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int X = std::clamp(x + dx, 0, w - 1), Y = std::clamp(y + dy, 0, h - 1);
                    const bool s = m[static_cast<size_t>(Y) * static_cast<size_t>(w) + static_cast<size_t>(X)];
                    v = dilate ? v || s : v && s;
                }
            out[static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)] = v;
        }
    return out;
}

// Pixels of one colour (within a few levels).
std::vector<bool> colour_mask(const Image& img, glm::vec3 rgb) {
    std::vector<bool> mask(static_cast<size_t>(img.width) * static_cast<size_t>(img.height));
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const uint8_t* p = img.at(x, y);
            bool same = true;
            for (int c = 0; c < 3; ++c) same = same && std::abs(p[c] - static_cast<int>(rgb[c] * 255.0f + 0.5f)) <= 3;
            mask[static_cast<size_t>(y) * static_cast<size_t>(img.width) + static_cast<size_t>(x)] = same;
        }
    return mask;
}

struct MaskDiff {
    size_t cap = 0, contour = 0, outside_band = 0;
};
// Cap pixels outside the contour grown by a pixel, and contour pixels shrunk
// by a pixel that the cap misses.
MaskDiff diff_masks(const std::vector<bool>& cap, const std::vector<bool>& contour, int w, int h) {
    const std::vector<bool> grown = morph(contour, w, h, true), shrunk = morph(contour, w, h, false);
    MaskDiff d;
    for (size_t i = 0; i < cap.size(); ++i) {
        d.cap += cap[i];
        d.contour += contour[i];
        d.outside_band += (cap[i] && !grown[i]) || (shrunk[i] && !cap[i]);
    }
    return d;
}

struct BuiltBlob {
    ContourStack stack;
    std::vector<Vec3f> positions;
    std::vector<uint32_t> indices;
};
BuiltBlob build_blob() {
    BuiltBlob b;
    b.stack = blob_stack(7);
    auto built = build_structures(b.stack, BuildOptions{}, "blob.contours.json");
    EXPECT_TRUE(built.ok()) << (built.ok() ? "" : built.error().message);
    if (!built.ok()) return b;
    const Mesh& mesh = built.value().at(0).mesh;
    EXPECT_TRUE(built.value().at(0).closed_manifold);
    for (const Vec3& p : mesh.positions) b.positions.emplace_back(p);
    b.indices = mesh.indices;
    return b;
}

constexpr glm::vec3 kCapRed{1.0f, 0.0f, 0.0f};

}  // namespace

// The plane on an input slice: the cap is the traced contour (1280x800, a
// camera looking down at an angle, so the projection is not a plain scale).
TEST(CutPlane, CapOnAnInputSliceIsTheTracedContour) {
    RenderFixture f(1280, 800);
    REQUIRE_GL(f);
    const BuiltBlob blob = build_blob();
    ASSERT_FALSE(blob.positions.empty());
    auto id = f.renderer().add_model({blob.positions, {}, blob.indices}, "blob");
    ASSERT_TRUE(id.ok());
    f.renderer().state(id.value())->color = Vec3f(0.6f, 0.65f, 0.7f);
    Vec3f lo, hi;
    ASSERT_TRUE(f.renderer().scene_box(lo, hi));
    for (size_t k : {2u, 3u, 4u}) {  // slices with one and with two contours
        const Slice& slice = blob.stack.slices[k];
        const float z = static_cast<float>(slice.z);
        View view = View::framing_box(lo, hi, Vec3f(0.25f, -0.35f, 1.0f), 1280.0f / 800.0f);
        FrameOptions o = f.frame();
        o.cut.enabled = true;
        o.cut.plane = glm::vec4(0.0f, 0.0f, 1.0f, -z);  // removes z > slice z, the side the camera is on
        o.cut.cap_color = glm::vec4(kCapRed, 1.0f);
        const Image img = f.draw(view, {}, o);
        const std::vector<bool> cap = colour_mask(img, kCapRed);
        const std::vector<bool> contour = contour_mask(slice, view, img.width, img.height);
        const MaskDiff d = diff_masks(cap, contour, img.width, img.height);
        EXPECT_GT(d.contour, 20000u) << "slice " << k << ": the contour covers a real part of the picture";
        EXPECT_EQ(d.outside_band, 0u) << "slice " << k << ": cap " << d.cap << " px, contour " << d.contour << " px";
        if (k == 3) expect_golden("cut_on_slice", img);
    }
}

// The section is found on the CPU once per plane and geometry: a still plane
// keeps it (and draws the same picture), a moved plane or a turned model
// finds it again.
TEST(CutPlane, SectionIsKeptWhileThePlaneStays) {
    RenderFixture f(640, 400);
    REQUIRE_GL(f);
    const BuiltBlob blob = build_blob();
    ASSERT_FALSE(blob.positions.empty());
    auto id = f.renderer().add_model({blob.positions, {}, blob.indices}, "blob");
    ASSERT_TRUE(id.ok());
    Vec3f lo, hi;
    ASSERT_TRUE(f.renderer().scene_box(lo, hi));
    const View view = View::framing_box(lo, hi, Vec3f(0.25f, -0.35f, 1.0f), 640.0f / 400.0f);
    FrameOptions o = f.frame();
    o.cut.enabled = true;
    o.cut.plane = glm::vec4(0.0f, 0.0f, 1.0f, -3.0f);
    o.cut.cap_color = glm::vec4(kCapRed, 1.0f);
    const Image first = f.draw(view, {}, o);
    EXPECT_EQ(f.renderer().last_frame_stats().cut_sections, 1u);
    const Image kept = f.draw(view, {}, o);
    EXPECT_EQ(f.renderer().last_frame_stats().cut_sections, 0u);
    EXPECT_EQ(first.rgba, kept.rgba);
    EXPECT_GT(diff_masks(colour_mask(kept, kCapRed), contour_mask(blob.stack.slices[3], view, 640, 400), 640, 400).cap,
              2000u);
    o.cut.plane.w = -2.0f;
    (void)f.draw(view, {}, o);
    EXPECT_EQ(f.renderer().last_frame_stats().cut_sections, 1u);
    // Raised by one, the model meets the plane z = 3 at its slice 2, now at z = 3: the same
    // plane in the model's space, so the section is kept and drawn where the model now is.
    f.renderer().state(id.value())->transform = glm::translate(glm::mat4(1.0f), Vec3f(0.0f, 0.0f, 1.0f));
    o.cut.plane.w = -3.0f;
    const Image raised = f.draw(view, {}, o);
    EXPECT_EQ(f.renderer().last_frame_stats().cut_sections, 0u);
    Slice slice2 = blob.stack.slices[2];
    slice2.z = 3.0;
    const MaskDiff d = diff_masks(colour_mask(raised, kCapRed), contour_mask(slice2, view, 640, 400), 640, 400);
    EXPECT_GT(d.contour, 2000u);
    EXPECT_EQ(d.outside_band, 0u);
    f.renderer().state(id.value())->transform = glm::translate(glm::mat4(1.0f), Vec3f(0.0f, 0.0f, 0.5f));
    (void)f.draw(view, {}, o);
    EXPECT_EQ(f.renderer().last_frame_stats().cut_sections, 1u);
}

// The same check must fail when the cap is off by a slice's worth of plane.
TEST(CutPlane, CapOffTheSliceIsNotTheContour) {
    RenderFixture f(640, 400);
    REQUIRE_GL(f);
    const BuiltBlob blob = build_blob();
    ASSERT_FALSE(blob.positions.empty());
    ASSERT_TRUE(f.renderer().add_model({blob.positions, {}, blob.indices}, "blob").ok());
    Vec3f lo, hi;
    ASSERT_TRUE(f.renderer().scene_box(lo, hi));
    View view = View::framing_box(lo, hi, Vec3f(0.25f, -0.35f, 1.0f), 640.0f / 400.0f);
    FrameOptions o = f.frame();
    o.cut.enabled = true;
    o.cut.plane = glm::vec4(0.0f, 0.0f, 1.0f, -3.5f);  // between slices 3 and 4
    o.cut.cap_color = glm::vec4(kCapRed, 1.0f);
    const Image img = f.draw(view, {}, o);
    const MaskDiff d =
        diff_masks(colour_mask(img, kCapRed), contour_mask(blob.stack.slices[3], view, 640, 400), 640, 400);
    EXPECT_GT(d.cap, 2000u);
    EXPECT_GT(d.outside_band, 100u);
}

namespace {

// A sphere, a turned cube and a torus in one style, cut by a tilted plane
// through all three, seen from the removed side.
struct CutScene {
    std::vector<ModelId> ids;
    View view;
    FrameOptions options;
};
CutScene cut_scene(RenderFixture& f, Style style) {
    static const test::GenMesh sphere = test::icosphere(3);
    static const test::GenMesh box = test::cube(0.8f);
    static const test::GenMesh ring = test::torus(48, 24, 0.8f, 0.3f);
    Renderer& r = f.renderer();
    CutScene c;
    struct Item {
        const test::GenMesh* mesh;
        glm::mat4 transform;
        Vec3f color;
    };
    const glm::mat4 one(1.0f);
    for (const Item& it :
         {Item{&sphere, glm::translate(one, Vec3f(-1.6f, 0, 0)), {0.85f, 0.45f, 0.4f}},
          Item{&box, glm::rotate(glm::translate(one, Vec3f(0.6f, 0, 0)), 0.6f, Vec3f(0, 1, 0)), {0.45f, 0.6f, 0.85f}},
          Item{&ring, glm::rotate(glm::translate(one, Vec3f(2.4f, 0, 0)), 1.2f, Vec3f(1, 0, 0)), {0.9f, 0.8f, 0.4f}}}) {
        auto id = r.add_model(it.mesh->data(), "item");
        EXPECT_TRUE(id.ok());
        ModelState* s = r.state(id.value());
        s->style = style;
        s->transform = it.transform;
        s->color = it.color;
        c.ids.push_back(id.value());
    }
    Vec3f center;
    float radius = 0;
    r.scene_bounds(center, radius);
    c.view = View::framing(center, radius, Vec3f(0.3f, 0.5f, 1.0f));
    c.options = f.frame();
    c.options.cut.enabled = true;
    c.options.cut.plane = glm::vec4(glm::normalize(Vec3f(0.15f, 0.3f, 1.0f)), -0.1f);
    return c;
}

}  // namespace

class CutStyleGolden : public ::testing::TestWithParam<Style> {};

// Each style cut and capped: the caps are in each model's colour, lit as a
// flat surface, and nothing of the removed side is drawn.
TEST_P(CutStyleGolden, MatchesGolden) {
    RenderFixture f(400, 250);
    REQUIRE_GL(f);
    CutScene c = cut_scene(f, GetParam());
    const Image img = f.draw(c.view, {}, c.options);
    expect_golden(std::string("cut_") + style_name(GetParam()), img);
    // Without caps the sections are holes: the picture changes where they were.
    c.options.cut.caps = false;
    const auto d = test::compare(img, f.draw(c.view, {}, c.options));
    EXPECT_GT(d.bad_block_fraction, 0.03);
}

INSTANTIATE_TEST_SUITE_P(AllStyles, CutStyleGolden,
                         ::testing::Values(Style::Smooth, Style::Wireframe, Style::Lines, Style::Hatching,
                                           Style::Hatching2Tone),
                         [](const auto& info) {
                             std::string n = style_name(info.param);
                             std::erase(n, '-');
                             return n;
                         });

// x-ray: one model selected (purple), the others faded; their caps blend too.
TEST(CutPlane, SelectionAndXray) {
    RenderFixture f(400, 250);
    REQUIRE_GL(f);
    CutScene c = cut_scene(f, Style::Smooth);
    f.renderer().state(c.ids[1])->selected = true;
    c.options.xray_unselected = true;
    expect_golden("cut_selection_xray", f.draw(c.view, {}, c.options));
}

// Each cap has its own model's colour: with a fixed cap colour the sections
// become that colour, and a model on the removed side is not drawn at all.
TEST(CutPlane, CapsPerModelAndRemovedModels) {
    RenderFixture f(400, 250);
    REQUIRE_GL(f);
    CutScene c = cut_scene(f, Style::Smooth);
    const Image own = f.draw(c.view, {}, c.options);
    c.options.cut.cap_color = glm::vec4(0.0f, 1.0f, 0.0f, 1.0f);
    const Image green = f.draw(c.view, {}, c.options);
    const std::vector<bool> green_mask = colour_mask(green, {0, 1, 0}), own_mask = colour_mask(own, {0, 1, 0});
    EXPECT_GT(std::count(green_mask.begin(), green_mask.end(), true), 2000);
    EXPECT_EQ(std::count(own_mask.begin(), own_mask.end(), true), 0);
    // Everything on the removed side: the frame is background only.
    c.options.cut.plane = glm::vec4(0.0f, 0.0f, -1.0f, 10.0f);
    EXPECT_EQ(f.renderer().last_frame_stats().models_drawn, 3u);
    const Image none = f.draw(c.view, {}, c.options);
    EXPECT_EQ(f.renderer().last_frame_stats().models_drawn, 0u);
    EXPECT_EQ(test::foreground_mask(none, f.frame().background).size(), static_cast<size_t>(400 * 250));
    const auto fg = test::foreground_mask(none, f.frame().background);
    EXPECT_EQ(std::count(fg.begin(), fg.end(), true), 0);
    // A model excluded from the cut (ModelState::cut = false, a group cut alone) is drawn whole.
    c.options.cut.plane = glm::vec4(glm::normalize(Vec3f(0.15f, 0.3f, 1.0f)), -0.1f);
    for (ModelId id : c.ids) f.renderer().state(id)->cut = false;
    const Image uncut = f.draw(c.view, {}, c.options);
    c.options.cut.enabled = false;
    EXPECT_EQ(test::compare(uncut, f.draw(c.view, {}, c.options)).bad_block_fraction, 0.0);
}
