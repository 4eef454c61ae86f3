// A progressive mesh whose index array went to the renderer for good
// (ModelSource::upload_mesh hands it over, packed until it fills the new
// element buffer, MeshData::index_fill; the buffer is the only copy and level
// changes are patched into it in place, MeshData::index_patch):
// every level draws what a fresh upload of that level from a mesh that kept
// its arrays draws, in the styles that read the element buffer back (lines,
// wireframe) and those that only draw it.
#include <gtest/gtest.h>

#include <vector>

#include "builder/lod/bpm_writer.h"
#include "builder/lod/simplify.h"
#include "kiosk/scene/model_source.h"
#include "shared/pm/bpm_reader.h"
#include "tests/render/bpm_models.h"
#include "tests/render/render_fixture.h"

namespace body::render {
using kiosk::ModelSource;
namespace {

using test::RenderFixture;

#define REQUIRE_GL(f) \
    if (!(f).ok()) GTEST_SKIP() << "no headless EGL: " << (f).why()

std::vector<uint8_t> torus_bpm() { return test::torus_bpm(48, 24); }
ModelSource source_of(const std::vector<uint8_t>& bytes) { return test::source_of(bytes, "torus.bpm"); }

// The buffer filled, patched and read back (lines, wireframe) with `access`.
void patched_buffer_draws_like_fresh_uploads(BufferAccess access) {
    const std::vector<uint8_t> bytes = torus_bpm();
    ASSERT_FALSE(bytes.empty());
    ModelSource given = source_of(bytes), kept = source_of(bytes);
    ASSERT_TRUE(given.progressive());
    RenderFixture f(200, 200, RendererOptions{access});
    REQUIRE_GL(f);
    ASSERT_EQ(f.renderer().buffer_access(), access);
    const MeshData first = given.upload_mesh();
    // Complete, with normals: handed over, packed until it fills the new buffer.
    ASSERT_TRUE(first.indices.empty());
    ASSERT_TRUE(static_cast<bool>(first.index_fill));
    ASSERT_EQ(first.index_fill_count, 3 * given.full_triangles());
    auto id = f.renderer().add_model(first, "torus");
    ASSERT_TRUE(id.ok()) << id.error().message;
    (void)given.take_dirty();
    given.release_arrays();
    // The source keeps no indices now: its uploads patch the buffer.
    EXPECT_TRUE(given.mesh().indices.empty());
    const View cam = View::framing(Vec3f(0.0f), 1.05f, Vec3f(0.3f, 0.6f, 1.0f));
    constexpr Style kStyles[] = {Style::Smooth, Style::Lines, Style::Wireframe};
    const std::vector<double> lods = {0.1, 0.5, 0.02, 1.0, 0.3, 0.3, 0.05};
    std::vector<Image> patched;  // per LOD, per style
    for (double lod : lods) {
        given.set_lod(lod);
        const MeshData patch = given.upload_mesh();
        EXPECT_TRUE(patch.indices.empty());
        EXPECT_TRUE(static_cast<bool>(patch.index_patch));
        EXPECT_TRUE(static_cast<bool>(patch.position_patch));
        const Status updated = f.renderer().update_model(id.value(), patch, given.take_dirty());
        ASSERT_TRUE(updated.ok()) << updated.error().message;
        for (Style style : kStyles) {
            f.renderer().state(id.value())->style = style;
            patched.push_back(f.draw(cam));
            EXPECT_EQ(f.renderer().last_frame_stats().triangles, given.triangles());
        }
    }
    // A level the buffer was not patched to draws otherwise (the test can fail).
    given.set_lod(0.5);
    f.renderer().state(id.value())->style = Style::Smooth;
    const Image stale = f.draw(cam);
    // Fresh uploads of each level from the source that kept its arrays, in a
    // second context made afterwards.
    RenderFixture g(200, 200);
    size_t at = 0;
    for (double lod : lods) {
        kept.set_lod(lod);
        auto fresh = g.renderer().add_model(kept.mesh(), "fresh");
        ASSERT_TRUE(fresh.ok()) << fresh.error().message;
        for (Style style : kStyles) {
            g.renderer().state(fresh.value())->style = style;
            const Image want = g.draw(cam);
            EXPECT_EQ(test::compare(patched[at++], want, 4).bad_block_fraction, 0.0)
                << style_name(style) << " at " << lod;
            if (lod == 0.05 && style == Style::Smooth) {
                EXPECT_EQ(test::compare(stale, want, 4).bad_block_fraction, 0.0);
            }
        }
        g.renderer().remove_model(fresh.value());
    }
    kept.set_lod(0.5);
    auto fresh = g.renderer().add_model(kept.mesh(), "fresh");
    ASSERT_TRUE(fresh.ok()) << fresh.error().message;
    g.renderer().state(fresh.value())->style = Style::Smooth;
    EXPECT_GT(test::compare(stale, g.draw(cam), 4).bad_block_fraction, 0.0);
    // Every write went the way asked (staged: the fill alone copied the whole
    // element buffer out of its temporary buffer); reads map in place.
    const TransferStats& t = f.renderer().transfer_stats();
    if (access == BufferAccess::Staged) {
        EXPECT_EQ(t.in_place_writes, 0u);
        EXPECT_GE(t.staged_bytes, 4 * first.index_fill_count);
    } else {
        EXPECT_GT(t.in_place_writes, lods.size());
        EXPECT_EQ(t.staged_bytes, 0u);
    }
    EXPECT_GT(t.in_place_maps, t.in_place_writes);  // lines and wireframe read back
}

TEST(RenderReleasedIndices, PatchedInPlaceDrawsLikeFreshUploads) {
    patched_buffer_draws_like_fresh_uploads(BufferAccess::InPlace);
}

// Staged (what a discrete GPU gets): the same images, written through temporary buffers.
TEST(RenderReleasedIndices, PatchedThroughStagingBuffersDrawsLikeFreshUploads) {
    patched_buffer_draws_like_fresh_uploads(BufferAccess::Staged);
}

TEST(RenderReleasedIndices, UpdateWithoutNormalsOrBeyondTheBufferIsRefused) {
    RenderFixture f(64, 64);
    REQUIRE_GL(f);
    const test::GenMesh s = test::icosphere(2);
    auto id = f.renderer().add_model(s.data(), "sphere");
    ASSERT_TRUE(id.ok());
    bool called = false;
    MeshData m;
    m.positions = s.positions;
    m.index_patch = [&](std::span<uint32_t>, size_t) { called = true; };
    m.index_patch_begin = 0;
    m.index_patch_end = 3;
    // No normals: area normals would need the indices.
    EXPECT_FALSE(f.renderer().update_model(id.value(), m, Dirty{0, 1, 0, 0}).ok());
    std::vector<Vec3f> normals(s.positions.size(), Vec3f(0, 0, 1));
    m.normals = normals;
    m.index_patch_end = s.indices.size() + 3;
    EXPECT_FALSE(f.renderer().update_model(id.value(), m, Dirty{}).ok());
    EXPECT_FALSE(called);
    // In range: the patch sees the buffer's window and what it writes is drawn.
    m.index_patch_begin = 3;
    m.index_patch_end = s.indices.size();
    m.index_patch = [&](std::span<uint32_t> window, size_t first) {
        called = window.size() == s.indices.size() - 3 && first == 3;
        for (uint32_t& i : window) i = 0;  // degenerate triangles: only the first one is left
    };
    const View cam = View::framing(Vec3f(0.0f), 1.0f);
    const Image before = f.draw(cam);
    ASSERT_TRUE(f.renderer().update_model(id.value(), m, Dirty{}).ok());
    EXPECT_TRUE(called);
    EXPECT_GT(test::compare(before, f.draw(cam), 4).bad_block_fraction, 0.0);
}

}  // namespace
}  // namespace body::render
