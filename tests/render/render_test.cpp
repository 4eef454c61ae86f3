// Renderer tests on llvmpipe (headless EGL): golden images with a tolerant
// metric, property checks, bad input, LOD patching, GLFW under Xvfb, softpipe.
#include <GLES3/gl3.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <span>

#include "kiosk/render/gl_util.h"
#include "kiosk/scene/model_source.h"
#include "shared/obj_io.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "tests/render/render_fixture.h"

using namespace body;
using namespace body::render;
using body::kiosk::load_model_file;
using body::kiosk::mesh_data_of;
using body::kiosk::ModelSource;
using body::test::RenderFixture;

namespace {

const std::string kGoldenDir = BODY_GOLDEN_DIR;

std::filesystem::path temp_dir() {
    auto d = std::filesystem::temp_directory_path() / ("body_render_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
}

#define REQUIRE_GL(fixture) \
    if (!(fixture).ok()) GTEST_SKIP() << "no headless EGL/GLES 3 (Mesa libegl1/libgl1-mesa-dri): " << (fixture).why()

int run(const std::string& cmd) {
    int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

// `bodygen lod` on the glmark2 bunny into temp_dir()/file. `skip` names a missing
// prerequisite; `path` is empty when bodygen failed.
struct BunnyBpm {
    std::string path, skip;
};
BunnyBpm make_bunny_bpm(const std::string& file) {
    const std::string bodygen = std::string(BODY_BINARY_DIR) + "/bin/bodygen";
    const std::string bunny = "/usr/share/glmark2/models/bunny.obj";
    if (!std::filesystem::exists(bodygen)) return {"", "bodygen not built"};
    if (!std::filesystem::exists(bunny)) return {"", "bunny.obj missing (Debian glmark2-data)"};
    const std::string bpm = (temp_dir() / file).string();
    if (run(bodygen + " lod " + bunny + " -o " + bpm + " >/dev/null") != 0) return {};
    return {bpm, ""};
}

// Sphere on the left, a turned cube on the right, in one style.
std::vector<ModelId> two_shapes(Renderer& r, Style style) {
    static const test::GenMesh sphere = test::icosphere(3);
    static const test::GenMesh box = test::cube(0.8f);
    auto a = r.add_model(sphere.data(), "sphere");
    auto b = r.add_model(box.data(), "cube");
    EXPECT_TRUE(a.ok() && b.ok());
    r.state(a.value())->style = style;
    r.state(a.value())->transform = glm::translate(glm::mat4(1.0f), Vec3f(-1.2f, 0, 0));
    r.state(b.value())->style = style;
    r.state(b.value())->color = Vec3f(0.45f, 0.6f, 0.85f);
    r.state(b.value())->transform = glm::rotate(
        glm::rotate(glm::translate(glm::mat4(1.0f), Vec3f(1.3f, 0, 0)), 0.6f, Vec3f(0, 1, 0)), 0.4f, Vec3f(1, 0, 0));
    return {a.value(), b.value()};
}

View scene_camera(Renderer& r) {
    Vec3f c;
    float radius = 0;
    r.scene_bounds(c, radius);
    return View::framing(c, radius, Vec3f(0.0f, 0.2f, 1.0f));
}

// The two shapes in one style and the camera that frames them.
View two_shapes_framed(Renderer& r, Style style) {
    two_shapes(r, style);
    return scene_camera(r);
}

// Compares with golden/<name>.png (BODY_UPDATE_GOLDENS=1 rewrites it).
void expect_golden(const std::string& name, const Image& img) {
    const std::string path = kGoldenDir + "/" + name + ".png";
    if (std::getenv("BODY_UPDATE_GOLDENS")) {
        ASSERT_TRUE(write_png(path, img).ok());
        return;
    }
    auto golden = read_png(path);
    ASSERT_TRUE(golden.ok()) << golden.error().message << " (regenerate with BODY_UPDATE_GOLDENS=1)";
    auto d = test::compare(golden.value(), img);
    if (d.bad_block_fraction > 0.01 || std::abs(d.mean_luma_delta) > 1.5) {
        (void)write_png((temp_dir() / (name + ".actual.png")).string(), img);
        ADD_FAILURE() << name << ": " << d.bad_block_fraction * 100 << "% blocks differ, mean luma delta "
                      << d.mean_luma_delta << " (actual written to " << temp_dir().string() << ")";
    }
}

}  // namespace

class StyleGolden : public ::testing::TestWithParam<Style> {};

TEST_P(StyleGolden, MatchesGolden) {
    RenderFixture f;
    REQUIRE_GL(f);
    Image img = f.draw(two_shapes_framed(f.renderer(), GetParam()));
    expect_golden(std::string("style_") + style_name(GetParam()), img);
}

INSTANTIATE_TEST_SUITE_P(AllStyles, StyleGolden,
                         ::testing::Values(Style::Smooth, Style::Wireframe, Style::Lines, Style::Hatching,
                                           Style::Hatching2Tone),
                         [](const auto& info) {
                             std::string n = style_name(info.param);
                             std::erase(n, '-');
                             return n;
                         });

namespace {
void mixed_scene(Renderer& r) {
    static const test::GenMesh sphere = test::icosphere(3);
    static const test::GenMesh box = test::cube(0.7f);
    static const test::GenMesh ring = test::torus(48, 24, 0.8f, 0.3f);
    struct Item {
        const test::GenMesh* mesh;
        Style style;
        Vec3f at;
        Vec3f color;
    };
    for (Item it : {Item{&sphere, Style::Smooth, {-1.8f, 0.0f, 0.0f}, {0.85f, 0.45f, 0.4f}},
                    Item{&box, Style::Lines, {0.0f, 0.0f, -0.5f}, {0.8f, 0.8f, 0.8f}},
                    Item{&ring, Style::Hatching, {1.9f, 0.0f, 0.0f}, {0.9f, 0.85f, 0.7f}},
                    Item{&sphere, Style::Hatching2Tone, {0.0f, 1.5f, 0.0f}, {0.9f, 0.9f, 0.9f}},
                    Item{&sphere, Style::Wireframe, {0.0f, -1.5f, 0.0f}, {0.4f, 0.6f, 0.9f}}}) {
        auto id = r.add_model(it.mesh->data(), "item");
        ASSERT_TRUE(id.ok());
        ModelState* s = r.state(id.value());
        s->style = it.style;
        s->color = it.color;
        s->transform = glm::rotate(glm::translate(glm::mat4(1.0f), it.at), 0.5f, Vec3f(1, 1, 0));
        if (it.style == Style::Wireframe) s->transform = glm::scale(s->transform, Vec3f(0.6f));
    }
}
}  // namespace

TEST(RenderGolden, MixedScene) {
    RenderFixture f(400, 250);
    REQUIRE_GL(f);
    mixed_scene(f.renderer());
    expect_golden("mixed_scene", f.draw(scene_camera(f.renderer())));
}

TEST(RenderGolden, SelectionAndXray) {
    RenderFixture f(400, 250);
    REQUIRE_GL(f);
    mixed_scene(f.renderer());
    auto ids = f.renderer().models();
    f.renderer().state(ids[1])->selected = true;  // the lines cube
    FrameOptions o = f.frame();
    o.xray_unselected = true;
    Image img = f.draw(scene_camera(f.renderer()), {}, o);
    expect_golden("selection_xray", img);
    // The selection is purple-dominant somewhere near the image centre.
    size_t purple = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const uint8_t* p = img.at(x, y);
            if (p[2] > p[1] + 40 && p[0] > p[1] + 20) ++purple;
        }
    EXPECT_GT(purple, 500u);
}

// The tolerance must not hide a missing line pass or a wrong hatching tone.
TEST(RenderGolden, MetricCatchesAMissingLinePass) {
    RenderFixture f;
    REQUIRE_GL(f);
    const View cam = two_shapes_framed(f.renderer(), Style::Lines);
    Image with = f.draw(cam);
    FrameOptions o = f.frame();
    o.ink = o.paper;  // edges drawn invisibly = no line pass
    Image without = f.draw(cam, {}, o);
    auto d = test::compare(with, without);
    EXPECT_GT(d.bad_block_fraction, 0.01);
    auto same = test::compare(with, f.draw(cam));
    EXPECT_EQ(same.bad_block_fraction, 0.0);
}

TEST(RenderGolden, MetricCatchesAWrongTone) {
    RenderFixture f;
    REQUIRE_GL(f);
    const View cam = two_shapes_framed(f.renderer(), Style::Hatching);
    Image right = f.draw(cam);
    Lighting darker;
    darker.key -= 0.15f;  // about one tone darker
    auto d = test::compare(right, f.draw(cam, darker));
    EXPECT_TRUE(d.bad_block_fraction > 0.01 || std::abs(d.mean_luma_delta) > 1.5)
        << d.bad_block_fraction << " " << d.mean_luma_delta;
}

TEST(RenderProperty, SilhouettePixelsLieOnTheOutline) {
    RenderFixture f(256, 256);
    REQUIRE_GL(f);
    test::GenMesh sphere = test::icosphere(4);
    auto id = f.renderer().add_model(sphere.data(), "sphere");
    ASSERT_TRUE(id.ok());
    View cam = View::framing(Vec3f(0.0f), 1.3f, Vec3f(0.3f, 0.2f, 1.0f));
    FrameOptions o = f.frame();
    // The object's outline from a flat fill.
    f.renderer().state(id.value())->style = Style::Baseline;
    f.renderer().state(id.value())->color = Vec3f(0.0f, 0.0f, 1.0f);
    Image fill = f.draw(cam, {}, o);
    auto mask = test::foreground_mask(fill, o.background, 40);
    const int w = fill.width, h = fill.height;
    auto in = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && mask[static_cast<size_t>(y * w + x)]; };
    std::vector<std::pair<int, int>> outline;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (in(x, y) && (!in(x - 1, y) || !in(x + 1, y) || !in(x, y - 1) || !in(x, y + 1)))
                outline.emplace_back(x, y);
    ASSERT_GT(outline.size(), 200u);
    // The same view in `lines`: every ink pixel near the outline, and the outline inked.
    f.renderer().state(id.value())->style = Style::Lines;
    Image lines = f.draw(cam, {}, o);
    std::vector<bool> ink(static_cast<size_t>(w * h));
    size_t ink_count = 0, far_from_outline = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (test::luma(lines.at(x, y)) < 128) {
                ink[static_cast<size_t>(y * w + x)] = true;
                ++ink_count;
                double best = 1e9;
                for (auto [ox, oy] : outline) best = std::min(best, std::hypot(ox - x, oy - y));
                if (best > 2.5) ++far_from_outline;
            }
    ASSERT_GT(ink_count, outline.size() / 2);
    EXPECT_EQ(far_from_outline, 0u) << "ink pixels away from the silhouette";
    size_t covered = 0;
    for (auto [ox, oy] : outline) {
        bool hit = false;
        for (int dy = -2; dy <= 2 && !hit; ++dy)
            for (int dx = -2; dx <= 2 && !hit; ++dx) {
                int x = ox + dx, y = oy + dy;
                hit = x >= 0 && y >= 0 && x < w && y < h && ink[static_cast<size_t>(y * w + x)];
            }
        covered += hit;
    }
    EXPECT_GT(static_cast<double>(covered) / static_cast<double>(outline.size()), 0.97);
}

TEST(RenderProperty, CubeCreasesAreDrawnInside) {
    RenderFixture f(256, 256);
    REQUIRE_GL(f);
    test::GenMesh box = test::cube(1.0f);
    auto id = f.renderer().add_model(box.data(), "cube");
    ASSERT_TRUE(id.ok());
    f.renderer().state(id.value())->style = Style::Lines;
    // Looking at a corner: the three visible creases meet in the middle.
    Image img = f.draw(View::framing(Vec3f(0.0f), 1.75f, Vec3f(1.0f, 1.0f, 1.0f)));
    int dark_near_centre = 0;
    for (int y = 120; y < 136; ++y)
        for (int x = 120; x < 136; ++x) dark_near_centre += test::luma(img.at(x, y)) < 128;
    EXPECT_GT(dark_near_centre, 6);
    // With a 100 degree threshold the 90 degree creases disappear.
    FrameOptions o = f.frame();
    o.crease_angle_deg = 100.0f;
    Image none = f.draw(View::framing(Vec3f(0.0f), 1.75f, Vec3f(1.0f, 1.0f, 1.0f)), {}, o);
    int dark = 0;
    for (int y = 120; y < 136; ++y)
        for (int x = 120; x < 136; ++x) dark += test::luma(none.at(x, y)) < 128;
    EXPECT_EQ(dark, 0);
}

// Edges between faces of the same normal can never be drawn (no silhouette,
// no crease), so `lines` leaves them out: a flat grid keeps its boundary only,
// and folding it keeps the edges along the fold too.
TEST(RenderProperty, LinesLeaveOutEdgesBetweenCoplanarFaces) {
    RenderFixture f(128, 128);
    REQUIRE_GL(f);
    constexpr uint32_t kQuads = 4, kRow = kQuads + 1;
    test::GenMesh grid;
    for (uint32_t y = 0; y < kRow; ++y)
        for (uint32_t x = 0; x < kRow; ++x)
            grid.positions.emplace_back(static_cast<float>(x) - 2.0f, static_cast<float>(y) - 2.0f, 0.0f);
    for (uint32_t y = 0; y < kQuads; ++y)
        for (uint32_t x = 0; x < kQuads; ++x) {
            const uint32_t a = y * kRow + x, b = a + 1, c = a + kRow, d = c + 1;
            grid.indices.insert(grid.indices.end(), {a, b, d, a, d, c});
        }
    const View camera = View::framing(Vec3f(0.0f), 3.0f, Vec3f(0.2f, 0.3f, 1.0f));
    auto flat = f.renderer().add_model(grid.data(), "flat grid");
    ASSERT_TRUE(flat.ok());
    f.renderer().state(flat.value())->style = Style::Lines;
    (void)f.draw(camera);
    EXPECT_EQ(f.renderer().last_frame_stats().edges, 4u * kQuads);  // 56 edges in all, 16 on the boundary
    f.renderer().remove_model(flat.value());

    test::GenMesh folded = grid;  // the right half turned up by 60 degrees about x = 0
    for (Vec3f& p : folded.positions)
        if (p.x > 0.0f) p = Vec3f(p.x * 0.5f, p.y, p.x * std::sqrt(3.0f) * 0.5f);
    auto fold = f.renderer().add_model(folded.data(), "folded grid");
    ASSERT_TRUE(fold.ok());
    f.renderer().state(fold.value())->style = Style::Lines;
    (void)f.draw(camera);
    EXPECT_EQ(f.renderer().last_frame_stats().edges, 4u * kQuads + kQuads);  // + the fold's 4 edges
}

// A plane tilted out of the axes and subdivided finely, in a box so large that
// the 16-bit position codes move its corners by up to a tenth of an edge: the
// face normals differ by rounding noise only, so `lines` still keeps just the
// boundary (coplanar_within_rounding), not the noisy interior edges.
TEST(RenderProperty, LinesLeaveOutEdgesOfAPlaneThatOnlyRoundingTilts) {
    RenderFixture f(128, 128);
    REQUIRE_GL(f);
    constexpr uint32_t kQuads = 32, kRow = kQuads + 1;
    const Vec3f u = glm::normalize(Vec3f(1.0f, 0.35f, 0.2f));
    const Vec3f w = glm::normalize(glm::cross(u, Vec3f(0.15f, 0.25f, 1.0f)));
    test::GenMesh plane;
    for (uint32_t y = 0; y < kRow; ++y)
        for (uint32_t x = 0; x < kRow; ++x)
            plane.positions.push_back(u * (10.0f * static_cast<float>(x) / kQuads) +
                                      w * (10.0f * static_cast<float>(y) / kQuads));
    for (uint32_t y = 0; y < kQuads; ++y)
        for (uint32_t x = 0; x < kQuads; ++x) {
            const uint32_t a = y * kRow + x, b = a + 1, c = a + kRow, d = c + 1;
            plane.indices.insert(plane.indices.end(), {a, b, d, a, d, c});
        }
    // A small far triangle makes the box 2000 units wide: a code step of 0.03,
    // a tenth of an edge of the grid.
    const auto far = static_cast<uint32_t>(plane.positions.size());
    plane.positions.insert(plane.positions.end(),
                           {Vec3f(2000.0f), Vec3f(2000.0f, 2001.0f, 2000.0f), Vec3f(2001.0f, 2000.0f, 2000.0f)});
    plane.indices.insert(plane.indices.end(), {far, far + 1, far + 2});
    auto id = f.renderer().add_model(plane.data(), "rounded plane");
    ASSERT_TRUE(id.ok());
    f.renderer().state(id.value())->style = Style::Lines;
    (void)f.draw(View::framing(Vec3f(5.0f), 10.0f, Vec3f(0.2f, 0.3f, 1.0f)));
    EXPECT_EQ(f.renderer().last_frame_stats().edges, 4u * kQuads + 3u);  // the grid's boundary and the far triangle's
}

TEST(RenderProperty, LineDataIsGivenBackInAnotherStyleAndRebuiltTheSame) {
    RenderFixture f(160, 160);
    REQUIRE_GL(f);
    test::GenMesh sphere = test::icosphere(3);
    auto id = f.renderer().add_model(sphere.data(), "sphere");
    ASSERT_TRUE(id.ok());
    const View cam = View::framing(Vec3f(0.0f), 1.1f, Vec3f(0.2f, 0.3f, 1.0f));
    const size_t without = f.renderer().gpu_bytes();
    // GLES 3.2: `wireframe` reads the position buffer through a buffer texture (no copy).
    const bool wire_buffer = render::gl_version_at_least(3, 2);
    for (Style line_style : {Style::Lines, Style::Wireframe}) {
        f.renderer().state(id.value())->style = line_style;
        const Image before = f.draw(cam);
        const size_t with = f.renderer().gpu_bytes();
        if (line_style == Style::Wireframe && wire_buffer)
            EXPECT_EQ(with, without) << "wireframe copied the positions although buffer textures are offered";
        else
            EXPECT_GT(with, without) << style_name(line_style);
        f.renderer().state(id.value())->selected = true;  // drawn purple, its style kept
        (void)f.draw(cam);
        f.renderer().state(id.value())->selected = false;
        f.renderer().state(id.value())->style = Style::Baseline;
        (void)f.draw(cam);
        EXPECT_EQ(f.renderer().gpu_bytes(), with) << "kept while selected and for the benchmark's baseline";
        f.renderer().state(id.value())->style = Style::Smooth;
        (void)f.draw(cam);
        EXPECT_EQ(f.renderer().gpu_bytes(), without) << style_name(line_style);
        f.renderer().state(id.value())->style = line_style;
        EXPECT_EQ(test::compare(f.draw(cam), before, 4).bad_block_fraction, 0.0) << style_name(line_style);
        EXPECT_EQ(f.renderer().gpu_bytes(), with);
    }
}

// The position textures (the path of GLES 3.0/3.1 boards, and of float
// positions) and the buffer texture (GLES 3.2) give `wireframe` the same codes,
// so the same picture; only the textures cost GPU bytes.
TEST(RenderProperty, WireframeFromPositionTexturesMatchesTheBufferTexture) {
    test::GenMesh sphere = test::icosphere(3);
    const View cam = View::framing(Vec3f(0.0f), 1.1f, Vec3f(0.2f, 0.3f, 1.0f));
    Image pictures[2];
    size_t added[2] = {0, 0};
    for (int textures = 0; textures < 2; ++textures) {
        RendererOptions options;
        options.wire_buffer_texture = textures == 0;
        RenderFixture f(160, 160, options);
        REQUIRE_GL(f);
        auto id = f.renderer().add_model(sphere.data(), "sphere");
        ASSERT_TRUE(id.ok());
        const size_t without = f.renderer().gpu_bytes();
        f.renderer().state(id.value())->style = Style::Wireframe;
        pictures[textures] = f.draw(cam);
        added[textures] = f.renderer().gpu_bytes() - without;
        const std::vector<bool> mask = test::foreground_mask(pictures[textures], f.frame().background, 3);
        EXPECT_GT(std::count(mask.begin(), mask.end(), true), 2000);  // the sphere was drawn
    }
    EXPECT_GT(added[1], 0u) << "the texture path made no position textures";
    EXPECT_EQ(test::compare(pictures[0], pictures[1], 4).bad_block_fraction, 0.0);
}

TEST(RenderProperty, HatchingDarkensMonotonicallyAsTheLightMovesAway) {
    for (Style style : {Style::Hatching, Style::Hatching2Tone}) {
        RenderFixture f(200, 200);
        REQUIRE_GL(f);
        test::GenMesh sphere = test::icosphere(4);
        auto id = f.renderer().add_model(sphere.data(), "sphere");
        ASSERT_TRUE(id.ok());
        f.renderer().state(id.value())->style = style;
        f.renderer().state(id.value())->color = Vec3f(1.0f);
        View cam = View::framing(Vec3f(0.0f), 1.2f, Vec3f(0.0f, 0.0f, 1.0f));
        std::vector<double> darkness;
        for (int deg = 0; deg <= 180; deg += 20) {
            Lighting l;
            float a = glm::radians(static_cast<float>(deg));
            l.key_dir = Vec3f(std::sin(a), 0.0f, std::cos(a));  // view space: +Z is toward the eye
            Image img = f.draw(cam, l);
            auto mask = test::foreground_mask(img, f.frame().background, 3);
            // The mask of a lit frame misses white paper; use the geometric disc instead.
            double sum = 0;
            size_t n = 0;
            for (int y = 0; y < img.height; ++y)
                for (int x = 0; x < img.width; ++x) {
                    double dx = x - 99.5, dy = y - 99.5;
                    if (dx * dx + dy * dy > 60.0 * 60.0) continue;
                    sum += 255.0 - test::luma(img.at(x, y));
                    ++n;
                }
            darkness.push_back(sum / static_cast<double>(n));
        }
        for (size_t i = 1; i < darkness.size(); ++i)
            EXPECT_GE(darkness[i], darkness[i - 1] - 0.25) << style_name(style) << " at " << i * 20 << " degrees";
        EXPECT_GT(darkness.back() - darkness.front(), 40.0) << style_name(style);
    }
}

TEST(RenderInput, BadModelFilesAreErrorsNotCrashes) {
    auto dir = temp_dir();
    const std::string garbage_obj = (dir / "garbage.obj").string();
    const std::string garbage_bpm = (dir / "garbage.bpm").string();
    const std::string bad_index = (dir / "bad_index.obj").string();
    std::ofstream(garbage_obj) << "\x01\x02 this is not an obj\nf 1 2\n";
    std::ofstream(garbage_bpm) << "BPM\0 definitely truncated";
    std::ofstream(bad_index) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n";
    for (const std::string& p :
         {garbage_obj, garbage_bpm, bad_index, (dir / "missing.obj").string(), (dir / "model.stl").string()}) {
        auto r = load_model_file(p);
        ASSERT_FALSE(r.ok()) << p;
        EXPECT_NE(r.error().message.find(std::filesystem::path(p).filename().string()), std::string::npos)
            << r.error().message;
        EXPECT_EQ(r.error().message.find('\n'), std::string::npos);
    }
}

TEST(RenderInput, RendererRejectsInconsistentMeshes) {
    RenderFixture f;
    REQUIRE_GL(f);
    std::vector<Vec3f> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    std::vector<uint32_t> bad = {0, 1, 7};
    EXPECT_FALSE(f.renderer().add_model({p, {}, bad}, "bad").ok());
    EXPECT_FALSE(f.renderer().add_model({{}, {}, {}}, "empty").ok());
    std::vector<uint32_t> good = {0, 1, 2};
    auto id = f.renderer().add_model({p, {}, good}, "tri");
    ASSERT_TRUE(id.ok());
    std::vector<Vec3f> more(10, Vec3f(0.0f));
    EXPECT_FALSE(f.renderer().update_model(id.value(), {more, {}, good}, {0, 10, 0, 0}).ok());
    EXPECT_FALSE(f.renderer().update_model(id.value() + 100, {p, {}, good}, {}).ok());
    EXPECT_EQ(f.renderer().models().size(), 1u);
}

// Patching index ranges (as a progressive mesh does) gives the same frame as a fresh upload.
TEST(RenderLod, DirtyRangeUpdatesMatchAFreshUpload) {
    for (Style style : {Style::Smooth, Style::Lines, Style::Wireframe}) {
        RenderFixture f(200, 200);
        REQUIRE_GL(f);
        test::GenMesh sphere = test::icosphere(2);
        // Explicit normals: computed ones would differ between the full and the half mesh.
        auto id = f.renderer().add_model({sphere.positions, sphere.positions, sphere.indices}, "full");
        ASSERT_TRUE(id.ok());
        f.renderer().state(id.value())->style = style;
        View cam = View::framing(Vec3f(0.0f), 1.1f, Vec3f(0.2f, 0.3f, 1.0f));
        (void)f.draw(cam);  // builds the lazily created data for the full mesh
        // Drop the second half of the triangles and flip one triangle's corner in place.
        std::vector<uint32_t> patched = sphere.indices;
        std::swap(patched[1], patched[2]);
        MeshData half{sphere.positions, sphere.positions, patched};
        half.index_count = patched.size() / 2 - (patched.size() / 2) % 3;
        ASSERT_TRUE(f.renderer().update_model(id.value(), half, {0, 0, 0, 3}).ok());
        Image patched_img = f.draw(cam);

        RenderFixture g(200, 200);
        std::vector<uint32_t> prefix(patched.begin(), patched.begin() + static_cast<long>(half.index_count));
        auto fresh = g.renderer().add_model({sphere.positions, sphere.positions, prefix}, "fresh");
        ASSERT_TRUE(fresh.ok());
        g.renderer().state(fresh.value())->style = style;
        Image fresh_img = g.draw(cam);
        auto d = test::compare(fresh_img, patched_img, 4);
        EXPECT_EQ(d.bad_block_fraction, 0.0) << style_name(style);
    }
}

TEST(RenderLod, ObjPreviewLodReducesTriangles) {
    test::GenMesh sphere = test::icosphere(4);
    ModelSource src("s", Vec3f(1.0f), sphere.positions, {}, sphere.indices);
    const size_t full = src.triangles();
    src.set_lod(0.25);
    EXPECT_LT(src.triangles(), full / 2);
    EXPECT_GT(src.triangles(), full / 10);
    Dirty d = src.take_dirty();
    EXPECT_EQ(d.index_end, src.mesh().indices.size());
}

namespace {
// Triangles as sorted rotations (the index codec may rotate a triangle's corners, keeping its winding).
std::vector<std::array<uint32_t, 3>> triangle_set(std::span<const uint32_t> idx) {
    std::vector<std::array<uint32_t, 3>> t;
    for (size_t f = 0; f + 2 < idx.size(); f += 3) {
        std::array<uint32_t, 3> a{idx[f], idx[f + 1], idx[f + 2]};
        while (a[0] != std::min({a[0], a[1], a[2]})) a = {a[1], a[2], a[0]};
        t.push_back(a);
    }
    std::sort(t.begin(), t.end());
    return t;
}
}  // namespace

TEST(RenderLod, ObjPreviewReleasedArraysComeBackWithTheSameTriangles) {
    test::GenMesh sphere = test::icosphere(4);
    ModelSource src("s", Vec3f(1.0f), sphere.positions, {}, sphere.indices);
    // The source renumbers vertices (fetch order) and keeps positions as 16-bit
    // codes: each of its vertices is an input vertex within half a code step.
    const MeshData first = src.mesh();
    ASSERT_EQ(first.positions.size(), sphere.positions.size());
    std::vector<uint32_t> input_vertex(first.positions.size(), UINT32_MAX);
    for (size_t v = 0; v < first.positions.size(); ++v)
        for (size_t w = 0; w < sphere.positions.size(); ++w)
            if (glm::length(first.positions[v] - sphere.positions[w]) < 2.0f / 65535.0f) input_vertex[v] = uint32_t(w);
    ASSERT_EQ(std::count(input_vertex.begin(), input_vertex.end(), UINT32_MAX), 0);
    auto in_input_numbers = [&](std::span<const uint32_t> idx) {
        std::vector<uint32_t> out(idx.size());
        for (size_t i = 0; i < idx.size(); ++i) out[i] = input_vertex[idx[i]];
        return triangle_set(out);
    };
    const auto full = triangle_set(first.indices);
    EXPECT_EQ(in_input_numbers(first.indices), triangle_set(sphere.indices));
    const std::vector<Vec3f> positions(first.positions.begin(), first.positions.end());
    (void)src.take_dirty();
    src.release_arrays();
    const MeshData again = src.mesh();
    EXPECT_EQ(triangle_set(again.indices), full);
    EXPECT_TRUE(std::equal(positions.begin(), positions.end(), again.positions.begin(), again.positions.end()));
    src.set_lod(0.25);
    const auto level = triangle_set(src.mesh().indices);
    ASSERT_LT(level.size(), full.size() / 2);
    EXPECT_EQ(level.size(), src.triangles());
    Dirty d = src.take_dirty();
    EXPECT_EQ(d.index_end, src.mesh().indices.size());
    src.release_arrays();
    EXPECT_EQ(triangle_set(src.mesh().indices), level);
    src.release_arrays();
    src.set_lod(1.0);
    EXPECT_EQ(src.triangles(), src.full_triangles());
    d = src.take_dirty();
    EXPECT_EQ(d.index_begin, 0u);
    EXPECT_EQ(d.index_end, src.mesh().indices.size());
    EXPECT_EQ(triangle_set(src.mesh().indices), full);
}

namespace {
std::string bodyview() { return std::string(BODY_BINARY_DIR) + "/bin/bodyview"; }

// Writes the two test shapes as one OBJ and returns its path.
std::string shapes_obj() {
    auto dir = temp_dir();
    std::string path = (dir / "shapes.obj").string();
    test::GenMesh s = test::icosphere(3);
    Mesh m;
    m.name = "sphere";
    for (auto& p : s.positions) m.positions.emplace_back(p);
    m.indices = s.indices;
    EXPECT_TRUE(write_obj(path, std::span<const Mesh>(&m, 1)).ok());
    return path;
}

}  // namespace

TEST(RenderCli, BadModelRendersNothingAndLogsOneLine) {
    auto dir = temp_dir();
    std::string bad = (dir / "broken.obj").string(), png = (dir / "broken.png").string(),
                log = (dir / "broken.log").string();
    std::ofstream(bad) << "v 0 0 0\nf 1 2 3\n";
    int rc = run(bodyview() + " --headless --size 160x100 --model " + bad + " --screenshot " + png + " 2>" + log);
    EXPECT_EQ(rc, 2);
    EXPECT_FALSE(std::filesystem::exists(png)) << "a picture of nothing was written";  // issue 30
    std::ifstream in(log);
    std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(std::count(all.begin(), all.end(), '\n'), 1) << all;
    EXPECT_NE(all.find("broken.obj"), std::string::npos) << all;
}

// --buffer-access reaches the renderer: a .bpm's index fill and level patches
// written through temporary buffers draw what they draw written in place, in
// the styles that read the buffers back too; an unknown value is refused in
// one line.
TEST(RenderCli, BufferAccessIsChosenOnTheCommandLine) {
    const BunnyBpm made = make_bunny_bpm("access_bunny.bpm");
    if (!made.skip.empty()) GTEST_SKIP() << made.skip;
    ASSERT_FALSE(made.path.empty()) << "bodygen lod failed";
    auto dir = temp_dir();
    std::string a = (dir / "in_place.png").string(), b = (dir / "staged.png").string(),
                log = (dir / "access.log").string();
    for (const char* style : {"smooth", "lines", "wireframe"}) {
        std::string args =
            std::string(" --headless --size 240x150 --lod 0.3 --style ") + style + " --model " + made.path;
        ASSERT_EQ(run(bodyview() + args + " --buffer-access in-place --screenshot " + a), 0);
        ASSERT_EQ(run(bodyview() + args + " --buffer-access staged --screenshot " + b), 0);
        auto ia = read_png(a), ib = read_png(b);
        ASSERT_TRUE(ia.ok() && ib.ok());
        EXPECT_EQ(test::compare(ia.value(), ib.value(), 4).bad_block_fraction, 0.0) << style;
    }
    EXPECT_EQ(run(bodyview() + " --headless --buffer-access sideways --model " + made.path + " --screenshot " + a +
                  " 2>" + log),
              2);
    std::ifstream in(log);
    std::string all((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(std::count(all.begin(), all.end(), '\n'), 1) << all;
    EXPECT_NE(all.find("sideways"), std::string::npos) << all;
}

TEST(RenderCli, SoftpipeFrameMatchesLlvmpipe) {
    auto dir = temp_dir();
    std::string obj = shapes_obj();
    std::string a = (dir / "llvmpipe.png").string(), b = (dir / "softpipe.png").string();
    for (const char* style : {"smooth", "lines", "hatching"}) {
        std::string args = std::string(" --headless --size 240x150 --style ") + style + " --model " + obj;
        ASSERT_EQ(run(bodyview() + args + " --screenshot " + a), 0);
        if (run("GALLIUM_DRIVER=softpipe " + bodyview() + args + " --screenshot " + b + " 2>/dev/null") != 0)
            GTEST_SKIP() << "softpipe unavailable (Mesa libgl1-mesa-dri)";
        auto ia = read_png(a), ib = read_png(b);
        ASSERT_TRUE(ia.ok() && ib.ok());
        auto d = test::compare(ia.value(), ib.value());
        EXPECT_LE(d.bad_block_fraction, 0.01) << style;
        EXPECT_LE(std::abs(d.mean_luma_delta), 1.5) << style;
    }
}

TEST(RenderCli, GlfwUnderXvfbMatchesHeadless) {
    if (run("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "xvfb-run missing (Debian xvfb)";
    auto dir = temp_dir();
    std::string obj = shapes_obj();
    std::string a = (dir / "headless.png").string(), b = (dir / "glfw.png").string();
    std::string args = " --size 240x150 --style smooth --model " + obj;
    ASSERT_EQ(run(bodyview() + " --headless" + args + " --screenshot " + a), 0);
    int rc = run("timeout 60 xvfb-run -a -s '-screen 0 640x480x24' " + bodyview() + " --platform glfw --windowed" +
                 args + " --screenshot " + b + " 2>" + (dir / "glfw.log").string());
    ASSERT_EQ(rc, 0) << "see " << (dir / "glfw.log").string();
    auto ia = read_png(a), ib = read_png(b);
    ASSERT_TRUE(ia.ok() && ib.ok());
    auto d = test::compare(ia.value(), ib.value());
    EXPECT_LE(d.bad_block_fraction, 0.01);
}

// The progressive-mesh path: a .bpm made by bodygen, uploaded once at full size,
// then moved between levels with the runtime's dirty ranges, must draw what a
// fresh upload of that level draws (refining and coarsening).
// A streaming model is added with only its first part written (prefix_only):
// the unwritten capacity (here: out-of-range indices) is
// neither validated nor uploaded, the prefix draws, and the rest arriving
// through update_model gives the same frame as a fresh upload of the whole.
TEST(RenderLod, PrefixOnlyAddLeavesCapacityForLaterUpdates) {
    RenderFixture f(200, 200);
    REQUIRE_GL(f);
    test::GenMesh sphere = test::icosphere(2);
    const size_t half = sphere.indices.size() / 2 - (sphere.indices.size() / 2) % 3;
    std::vector<Vec3f> positions = sphere.positions;
    std::vector<uint32_t> indices = sphere.indices;
    for (size_t i = half; i < indices.size(); ++i) indices[i] = 0xdeadbeefu;  // not written yet
    MeshData partial{positions, sphere.positions, indices};
    partial.index_count = half;
    // The box a fresh upload of the whole arrays computes, so that both keep
    // the same 16-bit position codes.
    partial.has_position_box = true;
    partial.position_box_min = partial.position_box_max = positions.front();
    for (const Vec3f& p : positions) {
        partial.position_box_min = glm::min(partial.position_box_min, p);
        partial.position_box_max = glm::max(partial.position_box_max, p);
    }
    EXPECT_FALSE(f.renderer().add_model(partial, "unwritten capacity").ok());  // whole arrays: invalid
    partial.prefix_only = true;
    auto id = f.renderer().add_model(partial, "streaming");
    ASSERT_TRUE(id.ok()) << id.error().message;
    const View cam = View::framing(Vec3f(0.0f), 1.1f, Vec3f(0.2f, 0.3f, 1.0f));
    Image first = f.draw(cam);
    // The rest arrives (while f's context is current).
    std::copy(sphere.indices.begin(), sphere.indices.end(), indices.begin());
    MeshData whole{positions, sphere.positions, indices};
    ASSERT_TRUE(f.renderer().update_model(id.value(), whole, {0, 0, half, indices.size()}).ok());
    Image full = f.draw(cam);

    RenderFixture g(200, 200);
    std::vector<uint32_t> prefix(sphere.indices.begin(), sphere.indices.begin() + static_cast<long>(half));
    auto fresh_half = g.renderer().add_model({sphere.positions, sphere.positions, prefix}, "fresh half");
    ASSERT_TRUE(fresh_half.ok());
    EXPECT_EQ(test::compare(g.draw(cam), first, 4).bad_block_fraction, 0.0);
    RenderFixture h(200, 200);
    auto fresh = h.renderer().add_model({sphere.positions, sphere.positions, sphere.indices}, "fresh");
    ASSERT_TRUE(fresh.ok());
    EXPECT_EQ(test::compare(h.draw(cam), full, 4).bad_block_fraction, 0.0);
    EXPECT_GT(test::compare(first, full, 4).bad_block_fraction, 0.0);  // the second half did show up
}

TEST(RenderLod, PatchOutsideThePositionBoxStillDrawsTheMovedVertices) {
    RenderFixture f(200, 200);
    REQUIRE_GL(f);
    test::GenMesh sphere = test::icosphere(3);
    auto id = f.renderer().add_model({sphere.positions, sphere.positions, sphere.indices}, "sphere");
    ASSERT_TRUE(id.ok());
    const View cam = View::framing(Vec3f(0.0f), 1.6f, Vec3f(0.2f, 0.3f, 1.0f));
    const Image small = f.draw(cam);
    // Every vertex moves 1.5x out: beyond the box the positions were coded in.
    std::vector<Vec3f> grown = sphere.positions;
    for (Vec3f& p : grown) p *= 1.5f;
    ASSERT_TRUE(f.renderer().update_model(id.value(), {grown, grown, sphere.indices}, {0, grown.size(), 0, 0}).ok());
    for (Style style : {Style::Smooth, Style::Wireframe, Style::Lines}) {
        f.renderer().state(id.value())->style = style;
        const Image patched = f.draw(cam);
        RenderFixture g(200, 200);
        auto fresh = g.renderer().add_model({grown, grown, sphere.indices}, "fresh");
        ASSERT_TRUE(fresh.ok());
        g.renderer().state(fresh.value())->style = style;
        // Codes in the new box against floats: a few pixels on the outline may differ.
        EXPECT_LT(test::compare(g.draw(cam), patched, 4).bad_block_fraction, 0.01) << style_name(style);
        if (style == Style::Smooth) {
            EXPECT_GT(test::compare(small, patched, 4).bad_block_fraction, 0.05);
        }
    }
}

TEST(RenderLod, PositionCodesDrawLikeTheirFloats) {
    RenderFixture f(200, 200);
    REQUIRE_GL(f);
    test::GenMesh sphere = test::icosphere(3);
    ModelSource src("s", Vec3f(1.0f), sphere.positions, {}, sphere.indices);
    const View cam = View::framing(Vec3f(0.0f), 1.1f, Vec3f(0.2f, 0.3f, 1.0f));
    MeshData codes_only = src.upload_mesh();
    ASSERT_TRUE(codes_only.positions.empty());
    ASSERT_EQ(codes_only.position_codes.size(), sphere.positions.size() * 3);
    codes_only.has_position_box = false;
    EXPECT_FALSE(f.renderer().add_model(codes_only, "no box").ok());
    auto coded = f.renderer().add_model(src.upload_mesh(), "codes");
    ASSERT_TRUE(coded.ok());
    for (Style style : {Style::Smooth, Style::Wireframe, Style::Lines}) {
        f.renderer().state(coded.value())->style = style;
        const Image from_codes = f.draw(cam);
        RenderFixture g(200, 200);
        MeshData floats = src.mesh();
        floats.position_codes = {};
        auto plain = g.renderer().add_model(floats, "floats");
        ASSERT_TRUE(plain.ok());
        g.renderer().state(plain.value())->style = style;
        EXPECT_EQ(test::compare(g.draw(cam), from_codes, 4).bad_block_fraction, 0.0) << style_name(style);
    }
}

TEST(RenderLod, ProgressiveMeshPatchesMatchFreshUploads) {
    const BunnyBpm made = make_bunny_bpm("bunny.bpm");
    if (!made.skip.empty()) GTEST_SKIP() << made.skip;
    ASSERT_FALSE(made.path.empty()) << "bodygen lod failed";
    const std::string& bpm = made.path;
    auto sources = load_model_file(bpm);
    ASSERT_TRUE(sources.ok()) << sources.error().message;
    ModelSource& src = sources.value().front();
    ASSERT_TRUE(src.progressive());
    RenderFixture f(200, 200);
    REQUIRE_GL(f);
    auto id = f.renderer().add_model(src.mesh(), "bunny");
    ASSERT_TRUE(id.ok());
    (void)src.take_dirty();
    const View cam = View::framing(Vec3f(0.0f), 1.1f, Vec3f(0.3f, 0.2f, 1.0f));
    struct Level {
        Style style;
        double lod;
        Image patched;
        std::vector<Vec3f> positions, normals;
        std::vector<uint32_t> prefix;
        bool has_box;
        Vec3f box_min, box_max;
    };
    std::vector<Level> levels;
    for (Style style : {Style::Smooth, Style::Lines}) {
        f.renderer().state(id.value())->style = style;
        for (double lod : {0.1, 0.5, 0.02, 1.0}) {
            src.set_lod(lod);
            ASSERT_TRUE(f.renderer().update_model(id.value(), src.mesh(), src.take_dirty()).ok());
            MeshData m = src.mesh();
            levels.push_back({style,
                              lod,
                              f.draw(cam),
                              {m.positions.begin(), m.positions.end()},
                              {m.normals.begin(), m.normals.end()},
                              {m.indices.begin(), m.indices.begin() + static_cast<long>(m.index_count)},
                              m.has_position_box,
                              m.position_box_min,
                              m.position_box_max});
        }
        EXPECT_EQ(src.triangles(), src.full_triangles());
    }
    // Fresh uploads of each level, in a second context made afterwards.
    RenderFixture g(200, 200);
    for (const Level& l : levels) {
        // In the patched model's position box: both draw the same 16-bit codes (the
        // box of a coarse level's own positions would round them onto another grid).
        MeshData fresh_data{l.positions, l.normals, l.prefix};
        fresh_data.has_position_box = l.has_box;
        fresh_data.position_box_min = l.box_min;
        fresh_data.position_box_max = l.box_max;
        auto fresh = g.renderer().add_model(fresh_data, "fresh");
        ASSERT_TRUE(fresh.ok());
        g.renderer().state(fresh.value())->style = l.style;
        auto d = test::compare(g.draw(cam), l.patched, 4);
        EXPECT_EQ(d.bad_block_fraction, 0.0) << style_name(l.style) << " at LOD " << l.lod;
        g.renderer().remove_model(fresh.value());
    }
}

// Geomorphs run in the vertex shader: vertices from morph_begin on are drawn at
// mix(morph source, position, morph). A square whose right side grows a spike
// (vertex 4, morph source on the square's edge): mid-morph the picture lies
// between the coarse and the fine one, nested, with the area in between.
TEST(RenderGeomorph, MidMorphLiesBetweenCoarseAndFine) {
    RenderFixture f(200, 200);
    REQUIRE_GL(f);
    const std::vector<Vec3f> positions = {
        {-0.5f, -0.5f, 0}, {0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}, {1.1f, 0.0f, 0}};
    const std::vector<Vec3f> sources = {positions[0], positions[1], positions[2], positions[3], {0.5f, 0.0f, 0}};
    const std::vector<Vec3f> normals(5, Vec3f(0, 0, 1));
    const std::vector<uint32_t> indices = {0, 1, 4, 0, 4, 2, 0, 2, 3};
    MeshData mesh{positions, normals, indices};
    mesh.morph_sources = sources;
    auto id = f.renderer().add_model(mesh, "spike");
    ASSERT_TRUE(id.ok()) << id.error().message;
    ModelState& st = *f.renderer().state(id.value());
    st.style = Style::Baseline;
    const View cam = View::framing(Vec3f(0.3f, 0, 0), 0.9f, Vec3f(0, 0, 1));
    const FrameOptions o = f.frame();
    auto mask_at = [&](float morph, size_t begin) {
        st.morph = morph;
        st.morph_begin = begin;
        return test::foreground_mask(f.draw(cam, {}, o), o.background);
    };
    auto area = [](const std::vector<bool>& m) { return static_cast<double>(std::count(m.begin(), m.end(), true)); };
    const auto coarse = mask_at(0.0f, 4), mid = mask_at(0.5f, 4), fine = mask_at(1.0f, 4);
    // Coarse: the square only; fine: with the spike; mid: half the spike's area.
    EXPECT_GT(area(fine), area(coarse) * 1.2);
    EXPECT_NEAR(area(mid) - area(coarse), 0.5 * (area(fine) - area(coarse)), 0.1 * (area(fine) - area(coarse)));
    size_t outside = 0;
    for (size_t i = 0; i < mid.size(); ++i) outside += (coarse[i] && !mid[i]) + (mid[i] && !fine[i]);
    EXPECT_LE(outside, 10u) << "mid-morph pixels outside the fine shape or coarse pixels missing";
    // Vertices before morph_begin do not move.
    EXPECT_EQ(mask_at(0.0f, 5), fine);
    // Sources patched in place (a morph starting / ending): at rest the source is
    // the position, so even morph 0 draws the fine shape.
    ASSERT_TRUE(f.renderer().set_morph_sources(id.value(), 4, std::span(positions).subspan(4)).ok());
    EXPECT_EQ(mask_at(0.0f, 4), fine);
    ASSERT_TRUE(f.renderer().set_morph_sources(id.value(), 4, std::span(sources).subspan(4)).ok());
    EXPECT_EQ(mask_at(0.0f, 4), coarse);
    EXPECT_FALSE(f.renderer().set_morph_sources(id.value(), 5, std::span(sources).subspan(4)).ok());
    // A model without morph sources ignores the factor.
    MeshData plain{positions, normals, indices};
    auto plain_id = f.renderer().add_model(plain, "plain");
    ASSERT_TRUE(plain_id.ok());
    f.renderer().state(id.value())->visible = false;
    f.renderer().state(plain_id.value())->style = Style::Baseline;
    f.renderer().state(plain_id.value())->morph = 0.0f;
    f.renderer().state(plain_id.value())->morph_begin = 4;
    EXPECT_EQ(test::foreground_mask(f.draw(cam, {}, o), o.background), fine);
}

// The kiosk's geomorph on a real progressive mesh: at the finer level with the
// sources of ProgressiveMesh::morph_sources(coarser level), morph 0 covers what the coarser
// level covers, morph 1 what the finer one does, and mid-morph lies in between.
TEST(RenderGeomorph, ProgressiveMeshMorphStartsAtTheCoarserLevel) {
    const BunnyBpm made = make_bunny_bpm("morph_bunny.bpm");
    if (!made.skip.empty()) GTEST_SKIP() << made.skip;
    ASSERT_FALSE(made.path.empty()) << "bodygen lod failed";
    const std::string& bpm = made.path;
    auto meshes = pm::read_bpm(bpm);
    ASSERT_TRUE(meshes.ok()) << meshes.error().message;
    pm::ProgressiveMesh& pm = *meshes.value().front();
    RenderFixture f(240, 240);
    REQUIRE_GL(f);
    const View cam = View::framing(Vec3f(0.0f), 1.1f, Vec3f(0.3f, 0.2f, 1.0f));
    const FrameOptions o = f.frame();
    auto mesh_now = [&] {
        MeshData m = mesh_data_of(pm);  // as the kiosk uploads a pm: its own codes
        m.morph_at_rest = true;
        return m;
    };
    const size_t lo = pm.level_for_triangles(300), hi = pm.level_for_triangles(3000);
    ASSERT_LT(lo, hi);
    pm.set_level(lo);
    auto coarse_id = f.renderer().add_model(mesh_now(), "coarse");
    ASSERT_TRUE(coarse_id.ok());
    f.renderer().state(coarse_id.value())->style = Style::Baseline;
    const auto coarse = test::foreground_mask(f.draw(cam, {}, o), o.background);
    f.renderer().state(coarse_id.value())->visible = false;

    pm.set_level(hi);
    pm.clear_dirty();
    auto id = f.renderer().add_model(mesh_now(), "fine");
    ASSERT_TRUE(id.ok());
    ModelState& st = *f.renderer().state(id.value());
    st.style = Style::Baseline;
    const auto fine = test::foreground_mask(f.draw(cam, {}, o), o.background);
    std::vector<Vec3f> sources;
    const size_t begin = pm.morph_sources(lo, sources);
    EXPECT_EQ(pm.level(), hi);
    EXPECT_EQ(begin + sources.size(), pm.vertex_count());
    ASSERT_TRUE(f.renderer().set_morph_sources(id.value(), begin, sources).ok());
    st.morph_begin = begin;
    auto differing = [](const std::vector<bool>& a, const std::vector<bool>& b) {
        size_t n = 0;
        for (size_t i = 0; i < a.size(); ++i) n += a[i] != b[i];
        return n;
    };
    st.morph = 0.0f;
    const auto start = test::foreground_mask(f.draw(cam, {}, o), o.background);
    st.morph = 0.5f;
    const auto mid = test::foreground_mask(f.draw(cam, {}, o), o.background);
    st.morph = 1.0f;
    EXPECT_EQ(test::foreground_mask(f.draw(cam, {}, o), o.background), fine);
    const size_t levels_apart = differing(coarse, fine);
    ASSERT_GT(levels_apart, 100u) << "the two levels should differ visibly";
    EXPECT_LT(differing(start, coarse), levels_apart / 20) << "morph 0 is not the coarse level";
    EXPECT_LT(differing(mid, coarse), levels_apart);
    EXPECT_LT(differing(mid, fine), levels_apart);
    EXPECT_GT(differing(mid, coarse), levels_apart / 10);
    EXPECT_GT(differing(mid, fine), levels_apart / 10);
}
