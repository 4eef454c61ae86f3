// A model's GL buffers grown as its data arrives (kiosk/render/buffer_growth.h):
// a streaming upload holds only what is written, and every later update that
// goes past it grows the buffers without changing what is drawn or read back.
#include <gtest/gtest.h>

#include <vector>

#include "tests/render/render_fixture.h"

namespace body::render {
namespace {

using test::RenderFixture;

#define REQUIRE_GL(f) \
    if (!(f).ok()) GTEST_SKIP() << "no headless EGL: " << (f).why()

constexpr int kRings = 48, kSegments = 24;

// The torus's first `rings` rings of vertices and the bands between them: a
// prefix of its arrays (band r joins rings r and r + 1; the last band closes the torus).
size_t prefix_vertices(int rings) { return static_cast<size_t>(rings * kSegments); }
size_t prefix_indices(int rings) { return static_cast<size_t>((rings == kRings ? kRings : rings - 1) * kSegments * 6); }

// Area-weighted normals of the whole torus, given with every upload (computed
// ones would differ along a prefix's open edge).
std::vector<Vec3f> normals_of(const test::GenMesh& t) {
    std::vector<Vec3f> n(t.positions.size(), Vec3f(0.0f));
    for (size_t f = 0; f + 2 < t.indices.size(); f += 3) {
        const uint32_t a = t.indices[f], b = t.indices[f + 1], c = t.indices[f + 2];
        const Vec3f fn = glm::cross(t.positions[b] - t.positions[a], t.positions[c] - t.positions[a]);
        n[a] += fn;
        n[b] += fn;
        n[c] += fn;
    }
    for (Vec3f& v : n) v = glm::normalize(v);
    return n;
}

MeshData with_box(MeshData d, const test::GenMesh& t) {
    Aabb box;
    for (const Vec3f& p : t.positions) box.extend(Vec3(p));
    d.has_position_box = true;
    d.position_box_min = Vec3f(box.min);
    d.position_box_max = Vec3f(box.max);
    return d;
}

TEST(RenderBufferGrowth, StreamedModelGrowsAndDrawsLikeAFreshUpload) {
    const test::GenMesh t = test::torus(kRings, kSegments, 0.7f, 0.3f);
    RenderFixture f(160, 120);
    REQUIRE_GL(f);
    Renderer& r = f.renderer();
    const size_t before = r.gpu_bytes();
    const std::vector<Vec3f> normals = normals_of(t);
    // Streaming: the arrays are the full capacity, two rings written.
    MeshData first = with_box(MeshData{t.positions, normals, t.indices}, t);
    first.prefix_only = true;
    first.vertex_count = prefix_vertices(2);
    first.index_count = prefix_indices(2);
    auto grown = r.add_model(first, "grown");
    ASSERT_TRUE(grown.ok()) << grown.error().message;
    const size_t full_bytes = t.positions.size() * (6 + 4) + t.indices.size() * 4;
    EXPECT_LT(r.gpu_bytes() - before, full_bytes / 4) << "buffers hold what is written, not the capacity";

    const View cam = View::framing(Vec3f(0.0f), 1.05f, Vec3f(0.3f, 0.6f, 1.0f));
    int written = 2;
    for (int rings : {3, 5, 11, 12, 30, kRings}) {
        const Dirty dirty{prefix_vertices(written), prefix_vertices(rings), prefix_indices(written),
                          prefix_indices(rings)};
        MeshData update = with_box(MeshData{t.positions, normals, t.indices}, t);
        update.vertex_count = prefix_vertices(rings);
        update.index_count = prefix_indices(rings);
        const Status st = r.update_model(grown.value(), update, dirty);
        ASSERT_TRUE(st.ok()) << st.error().message;
        written = rings;
        // The same prefix uploaded whole.
        const std::vector<Vec3f> pos(t.positions.begin(),
                                     t.positions.begin() + static_cast<std::ptrdiff_t>(prefix_vertices(rings)));
        const std::vector<uint32_t> idx(t.indices.begin(),
                                        t.indices.begin() + static_cast<std::ptrdiff_t>(prefix_indices(rings)));
        const std::vector<Vec3f> nrm(normals.begin(), normals.begin() + static_cast<std::ptrdiff_t>(pos.size()));
        auto fresh = r.add_model(with_box(MeshData{pos, nrm, idx}, t), "fresh");
        ASSERT_TRUE(fresh.ok()) << fresh.error().message;
        for (Style style : {Style::Smooth, Style::Wireframe, Style::Lines}) {
            r.state(grown.value())->style = r.state(fresh.value())->style = style;
            r.state(grown.value())->visible = true;
            r.state(fresh.value())->visible = false;
            const Image a = f.draw(cam);
            r.state(grown.value())->visible = false;
            r.state(fresh.value())->visible = true;
            const Image b = f.draw(cam);
            EXPECT_EQ(a.rgba, b.rgba) << rings << " rings, style " << style_name(style);
        }
        r.state(grown.value())->visible = true;
        std::vector<uint32_t> back;
        ASSERT_TRUE(r.read_indices(grown.value(), idx.size(),
                                   [&](std::span<const uint32_t> s) { back.assign(s.begin(), s.end()); }));
        EXPECT_EQ(back, idx) << rings << " rings: the element buffer read back";
        std::vector<Vec3f> fresh_positions, grown_positions;
        ASSERT_TRUE(r.read_positions(fresh.value(), fresh_positions));
        ASSERT_TRUE(r.read_positions(grown.value(), grown_positions));
        EXPECT_EQ(grown_positions, fresh_positions) << rings << " rings: the positions read back";
        r.remove_model(fresh.value());
    }
    // Grown to the capacity, no further.
    EXPECT_TRUE(r.read_indices(grown.value(), t.indices.size(), [](std::span<const uint32_t>) {}));
    EXPECT_FALSE(r.read_indices(grown.value(), t.indices.size() + 1, [](std::span<const uint32_t>) {}));
}

}  // namespace
}  // namespace body::render
