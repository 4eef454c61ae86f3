// The renderer's programs are linked at their first draw (kiosk/render/programs.h):
// a frame links only the programs of the styles it draws, a later frame links
// none of them again, and a style first drawn after others gives the same
// picture as from a renderer that had linked every program before.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "kiosk/render/program_binary.h"
#include "shared/style.h"
#include "tests/render/render_fixture.h"

namespace body::render {
namespace {

using test::RenderFixture;

#define REQUIRE_GL(f) \
    if (!(f).ok()) GTEST_SKIP() << "no headless EGL: " << (f).why()

// A sphere and a cube side by side, both in `style`; returns their ids.
std::vector<ModelId> add_pair(Renderer& r, Style style) {
    std::vector<ModelId> ids;
    const test::GenMesh sphere = test::icosphere(3), box = test::cube(0.6f);
    for (const test::GenMesh* mesh : {&sphere, &box}) {
        auto id = r.add_model(mesh->data(), "model");
        EXPECT_TRUE(id);
        ids.push_back(id.value());
        r.state(id.value())->style = style;
        r.state(id.value())->transform = glm::translate(glm::mat4(1.0f), Vec3f(ids.size() == 1 ? -0.9f : 0.9f, 0, 0));
    }
    return ids;
}

void set_style(Renderer& r, const std::vector<ModelId>& ids, Style style) {
    for (ModelId id : ids) r.state(id)->style = style;
}

View camera() {
    View v;
    v.eye = Vec3f(0.0f, 0.6f, 5.0f);
    return v;
}

TEST(RenderPrograms, AFrameLinksOnlyWhatItDrawsAndNothingTwice) {
    RenderFixture f(160, 100);
    REQUIRE_GL(f);
    Renderer& r = f.renderer();
    const auto ids = add_pair(r, Style::Smooth);
    (void)f.draw(camera());
    // Smooth: one program (the batched or the per-model one), not the table of six.
    EXPECT_EQ(r.last_frame_stats().programs_linked, 1u);
    (void)f.draw(camera());
    EXPECT_EQ(r.last_frame_stats().programs_linked, 0u);
    set_style(r, ids, Style::Wireframe);
    (void)f.draw(camera());
    EXPECT_EQ(r.last_frame_stats().programs_linked, 1u);
    set_style(r, ids, Style::Smooth);
    (void)f.draw(camera());
    EXPECT_EQ(r.last_frame_stats().programs_linked, 0u);
}

TEST(RenderPrograms, AStyleLinkedAtItsFirstDrawDrawsTheSamePicture) {
    for (Style style : kAllStyles) {
        if (style == Style::Smooth) continue;
        render::Image lazily, after_all;
        {
            RenderFixture f(160, 100);
            REQUIRE_GL(f);
            const auto ids = add_pair(f.renderer(), Style::Smooth);
            (void)f.draw(camera());
            set_style(f.renderer(), ids, style);
            lazily = f.draw(camera());
            EXPECT_GE(f.renderer().last_frame_stats().programs_linked, 1u) << style_name(style);
        }
        {
            RenderFixture f(160, 100);
            REQUIRE_GL(f);
            const auto ids = add_pair(f.renderer(), Style::Smooth);
            for (Style other : kAllStyles) {  // every style drawn once: every program linked
                set_style(f.renderer(), ids, other);
                (void)f.draw(camera());
            }
            set_style(f.renderer(), ids, style);
            after_all = f.draw(camera());
            EXPECT_EQ(f.renderer().last_frame_stats().programs_linked, 0u) << style_name(style);
        }
        ASSERT_EQ(lazily.rgba.size(), after_all.rgba.size());
        const test::ImageDiff d = test::compare(lazily, after_all, 8);
        EXPECT_EQ(d.bad_block_fraction, 0.0) << style_name(style);
        // Not an empty picture: the models cover part of it.
        size_t shown = 0;
        for (bool b : test::foreground_mask(lazily, Vec3f(lazily.rgba[0], lazily.rgba[1], lazily.rgba[2]) / 255.0f))
            shown += b;
        EXPECT_GT(shown, lazily.rgba.size() / 4 / 20) << style_name(style);
    }
}

// With a binary directory (program_binary.h): a program linked once is loaded
// from its binary in a later context and draws the same picture; a damaged
// binary is compiled again (same picture) and written anew.
TEST(RenderPrograms, ALaterContextLoadsTheProgramsBinaryAndDrawsTheSamePicture) {
    const std::string dir = testing::TempDir() + "program_binaries_" + std::to_string(::getpid());
    std::filesystem::remove_all(dir);
    set_program_binary_dir(dir);
    struct Off {
        std::string dir;
        ~Off() {
            set_program_binary_dir({});
            std::filesystem::remove_all(dir);
        }
    } off{dir};
    const auto draw_smooth = [](size_t& loaded) {
        RenderFixture f(160, 100);
        if (!f.ok()) return render::Image{};
        const size_t before = program_binaries_loaded();
        (void)add_pair(f.renderer(), Style::Smooth);
        render::Image img = f.draw(camera());
        loaded = program_binaries_loaded() - before;
        return img;
    };
    size_t loaded = 0;
    {
        RenderFixture probe(16, 16);
        REQUIRE_GL(probe);
        GLint formats = 0;
        glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
        if (formats == 0) GTEST_SKIP() << "the driver offers no program binary format";
    }
    const render::Image compiled = draw_smooth(loaded);
    EXPECT_EQ(loaded, 0u);
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir)) files.push_back(e.path());
    ASSERT_EQ(files.size(), 1u);  // the smooth program the frame drew
    const render::Image from_binary = draw_smooth(loaded);
    EXPECT_EQ(loaded, 1u);
    EXPECT_EQ(from_binary.rgba, compiled.rgba);
    // Damaged past its key: refused, compiled again, rewritten.
    const auto size = std::filesystem::file_size(files[0]);
    {
        std::fstream io(files[0], std::ios::in | std::ios::out | std::ios::binary);
        io.seekp(std::streamoff(size - 64));
        const std::string junk(64, 'x');
        io.write(junk.data(), 64);
    }
    const render::Image recompiled = draw_smooth(loaded);
    EXPECT_EQ(loaded, 0u);
    EXPECT_EQ(recompiled.rgba, compiled.rgba);
    (void)draw_smooth(loaded);
    EXPECT_EQ(loaded, 1u);  // the rewritten binary
    EXPECT_EQ(load_program_binary("a key never linked"), 0u);
}

}  // namespace
}  // namespace body::render
