// Batched drawing (kiosk/render/batch.h): a scene of 300 small models (position
// and normal codes, as a .bpm gives them; more than one chunk) drawn batched
// and one call a model must give the same bytes, the batched one in a few
// calls, through level-of-detail prefixes, colour, transform and style
// changes, selection, hidden and removed models, and streamed models whose
// buffers grow past their room in a chunk after it formed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "kiosk/render/batch.h"
#include "shared/pm/quantize.h"
#include "tests/render/render_fixture.h"

namespace body::render {
namespace {

using test::RenderFixture;

#define REQUIRE_GL(f) \
    if (!(f).ok()) GTEST_SKIP() << "no headless EGL: " << (f).why()

constexpr int kModels = 300;

// The .bpm writer's 8:8 octahedral code of a unit vector.
void encode(const Vec3f& n, uint8_t out[2]) { pm::oct_encode8(n.x, n.y, n.z, out); }

struct Shape {
    test::GenMesh mesh;
    std::vector<uint8_t> codes;
    MeshData data(size_t index_count = SIZE_MAX) const {
        MeshData d{mesh.positions, {}, mesh.indices};
        d.normal_codes = codes;
        d.index_count = index_count;
        return d;
    }
};

// A streamed model's upload: the faces ordered by their highest vertex, so a
// prefix of them uses a prefix of the vertices; `faces` of them and the
// vertices they use, the rest capacity (MeshData::prefix_only), in the box of
// every vertex.
MeshData streamed(const Shape& shape, std::vector<uint32_t>& sorted, size_t faces) {
    if (sorted.empty()) {
        const std::vector<uint32_t>& ix = shape.mesh.indices;
        std::vector<size_t> order(ix.size() / 3);
        for (size_t f = 0; f < order.size(); ++f) order[f] = f;
        auto top = [&](size_t f) { return std::max({ix[f * 3], ix[f * 3 + 1], ix[f * 3 + 2]}); };
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return top(a) < top(b); });
        for (size_t f : order)
            sorted.insert(sorted.end(), ix.begin() + ptrdiff_t(f * 3), ix.begin() + ptrdiff_t(f * 3 + 3));
    }
    MeshData d{shape.mesh.positions, {}, sorted};
    d.normal_codes = shape.codes;
    d.index_count = faces * 3;
    d.vertex_count = 1 + *std::max_element(sorted.begin(), sorted.begin() + ptrdiff_t(faces * 3));
    d.prefix_only = true;
    d.has_position_box = true;
    d.position_box_min = d.position_box_max = shape.mesh.positions[0];
    for (const Vec3f& p : shape.mesh.positions) {
        d.position_box_min = glm::min(d.position_box_min, p);
        d.position_box_max = glm::max(d.position_box_max, p);
    }
    return d;
}

Shape make_shape(int kind) {
    Shape s;
    s.mesh = kind == 0 ? test::icosphere(2, 0.9f) : test::torus(12, 16, 0.7f, 0.3f);
    s.codes.resize(s.mesh.positions.size() * 2);
    for (size_t v = 0; v < s.mesh.positions.size(); ++v) {
        const Vec3f p = s.mesh.positions[v];
        // The torus' normal points away from its ring; the sphere's from its centre.
        const Vec3f ring = kind == 0 ? Vec3f(0.0f) : 0.7f * glm::normalize(Vec3f(p.x, p.y, 0.0f));
        encode(glm::normalize(p - ring), &s.codes[v * 2]);
    }
    return s;
}

struct Frames {
    std::vector<Image> images;
    std::vector<size_t> draw_calls, models_drawn;
};

// The same scene and edits with batching on or off; an image after each step.
Frames run(bool batch) {
    Frames out;
    RendererOptions options;
    options.batch = batch;
    RenderFixture f(320, 240, options);
    if (!f.ok()) return out;
    Renderer& r = f.renderer();
    const Shape shapes[2] = {make_shape(0), make_shape(1)};
    std::vector<uint32_t> sorted[2];
    std::vector<ModelId> ids;
    // Every fifth model streams: a third of its faces first.
    auto is_streamed = [](int i) { return i % 5 == 2; };
    for (int i = 0; i < kModels; ++i) {
        const Shape& shape = shapes[i % 2];
        const size_t faces = shape.mesh.indices.size() / 3;
        auto id =
            r.add_model(is_streamed(i) ? streamed(shape, sorted[i % 2], faces / 3) : shape.data(), std::to_string(i));
        if (!id) return out;
        ids.push_back(id.value());
        ModelState& st = *r.state(id.value());
        const float x = static_cast<float>(i % 20) * 2.2f - 21.0f, y = static_cast<float>(i / 20) * 2.2f - 15.0f;
        st.transform = glm::translate(glm::mat4(1.0f), Vec3f(x, y, 0.3f * static_cast<float>(i % 5)));
        st.transform = glm::rotate(st.transform, 0.37f * static_cast<float>(i), glm::normalize(Vec3f(1, 2, 3)));
        st.transform = glm::scale(st.transform, i % 4 == 0 ? Vec3f(1.2f, 0.8f, 1.0f) : Vec3f(1.0f));
        st.color = Vec3f(0.2f + 0.6f * static_cast<float>(i % 7) / 6.0f, 0.3f + 0.5f * static_cast<float>(i % 5) / 4.0f,
                         0.9f - 0.6f * static_cast<float>(i % 3) / 2.0f);
        st.style = i % 3 == 0 ? Style::Baseline : i % 13 == 0 ? Style::Hatching : Style::Smooth;
        st.visible = i % 11 != 5;
        st.selected = i == 42;
    }
    const View cam = View::framing(Vec3f(0.0f), 25.0f, Vec3f(0.2f, 0.3f, 1.0f));
    auto take = [&] {
        out.images.push_back(f.draw(cam));
        out.draw_calls.push_back(r.last_frame_stats().draw_calls);
        out.models_drawn.push_back(r.last_frame_stats().models_drawn);
    };
    take();
    // Levels of detail: a third of the models draw a prefix of their triangles;
    // the streamed ones get the rest of their vertices and faces.
    for (int i = 0; i < kModels; ++i) {
        const Shape& shape = shapes[i % 2];
        const size_t faces = shape.mesh.indices.size() / 3;
        const ModelId id = ids[static_cast<size_t>(i)];
        if (is_streamed(i)) {
            const MeshData part = streamed(shape, sorted[i % 2], faces / 3),
                           all = streamed(shape, sorted[i % 2], faces);
            if (!r.update_model(id, all, Dirty{part.vertex_count, all.vertex_count, part.index_count, all.index_count})
                     .ok())
                return out;
        } else if (i % 3 == 0) {
            if (!r.update_model(id, shape.data(faces / 3 * 3), Dirty{}).ok()) return out;
        }
    }
    take();
    // Colours, transforms and styles change; one model leaves the scene; the
    // view moves (models leave the frustum).
    for (int i = 1; i < kModels; i += 4) {
        ModelState& st = *r.state(ids[static_cast<size_t>(i)]);
        st.color = Vec3f(1.0f) - st.color;
        st.transform = glm::translate(st.transform, Vec3f(0.0f, 0.0f, 1.0f));
        if (i % 20 == 1) st.style = Style::Wireframe;
    }
    r.state(ids[10])->style = Style::Baseline;
    r.state(ids[42])->selected = false;
    r.remove_model(ids[7]);
    take();
    out.images.push_back(f.draw(View::framing(Vec3f(-12.0f, -8.0f, 0.0f), 8.0f, Vec3f(0.1f, 0.2f, 1.0f))));
    out.draw_calls.push_back(r.last_frame_stats().draw_calls);
    out.models_drawn.push_back(r.last_frame_stats().models_drawn);
    return out;
}

TEST(RenderBatch, SamePixelsAsOneCallAModelInFewCalls) {
    {
        RenderFixture probe(16, 16);
        REQUIRE_GL(probe);
    }
    const Frames single = run(false), batched = run(true);
    ASSERT_EQ(single.images.size(), 4u);
    ASSERT_EQ(batched.images.size(), 4u);
    for (size_t k = 0; k < single.images.size(); ++k) {
        SCOPED_TRACE("step " + std::to_string(k));
        EXPECT_EQ(single.models_drawn[k], batched.models_drawn[k]);
        EXPECT_TRUE(single.images[k].rgba == batched.images[k].rgba);
        // One call a model without batching; with it, the hatched, wireframe
        // and selected models one each, the rest a few per chunk.
        EXPECT_GE(single.draw_calls[k], single.models_drawn[k]);
        EXPECT_LT(batched.draw_calls[k], single.models_drawn[k] / 4);
    }
    // Each step changed the picture (the comparison above can fail).
    for (size_t k = 1; k < batched.images.size(); ++k)
        EXPECT_FALSE(batched.images[k].rgba == batched.images[k - 1].rgba) << "step " << k;
    // The scene is on screen: a good part of the view shows models.
    const Image& first = batched.images[0];
    const std::vector<bool> fg = test::foreground_mask(first, Vec3f(0.97f, 0.96f, 0.93f));
    EXPECT_GT(std::count(fg.begin(), fg.end(), true), static_cast<long>(fg.size() / 8));
}

// A streamed start draws its first frame before most models have arrived, and
// the rest join over the next frames: once all are in, they draw in as many
// calls as the same models added before the first frame (the last chunk's free
// slots are filled before a new chunk is made), with the same pixels, and a
// frame after that links no program.
TEST(RenderBatch, ModelsArrivingOverFramesDrawInAsFewCallsAsAtOnce) {
    constexpr int kArriving = 120, kPerFrame = 12;
    const Shape shapes[2] = {make_shape(0), make_shape(1)};
    const View cam = View::framing(Vec3f(0.0f), 14.0f, Vec3f(0.2f, 0.3f, 1.0f));
    std::vector<Image> images;
    std::vector<size_t> draw_calls;
    for (int per_frame : {kArriving, kPerFrame}) {
        RenderFixture f(200, 160);
        REQUIRE_GL(f);
        Renderer& r = f.renderer();
        for (int i = 0; i < kArriving; ++i) {
            auto id = r.add_model(shapes[i % 2].data(), std::to_string(i));
            ASSERT_TRUE(id);
            ModelState& st = *r.state(id.value());
            st.transform = glm::translate(glm::mat4(1.0f), Vec3f(static_cast<float>(i % 12) * 2.2f - 12.0f,
                                                                 static_cast<float>(i / 12) * 2.2f - 10.0f, 0.0f));
            st.color = Vec3f(0.3f + 0.6f * static_cast<float>(i % 7) / 6.0f, 0.5f, 0.8f);
            st.style = i % 3 == 0 ? Style::Baseline : Style::Smooth;
            if ((i + 1) % per_frame == 0) (void)f.draw(cam);  // a frame with the models arrived so far
        }
        images.push_back(f.draw(cam));
        ASSERT_EQ(r.last_frame_stats().models_drawn, static_cast<size_t>(kArriving));
        draw_calls.push_back(r.last_frame_stats().draw_calls);
        EXPECT_EQ(r.last_frame_stats().programs_linked, 0u);
    }
    EXPECT_EQ(draw_calls[1], draw_calls[0]);
    EXPECT_LE(draw_calls[0], 2u * ((kArriving + 7) / 8));  // batched: at least 8 models a chunk, 2 styles
    EXPECT_TRUE(images[1].rgba == images[0].rgba);
}

// A chunk draws its models nearest first, whatever the order they arrived in
// (a streamed start adds them as their files arrive): the front structures fill
// the depth buffer before the ones behind them are shaded. Two coplanar squares
// facing the camera, overlapping in the middle, each with a small triangle off
// the plane (near for "front", far for "back") that moves its bounding sphere;
// the same quantization box for both, so the squares' depths are equal bit for
// bit and, under the depth test's LEQUAL, the one drawn last shows where they
// overlap: "back", in the same picture whichever model came first.
TEST(RenderBatch, NearerModelsDrawFirstWhateverOrderTheyArrived) {
    auto make = [](float x0, float tri_x, float tri_z) {
        Shape s;
        s.mesh.positions = {Vec3f(x0, -1, 0),         Vec3f(x0 + 2, -1, 0),       Vec3f(x0 + 2, 1, 0),
                            Vec3f(x0, 1, 0),          Vec3f(tri_x, -0.2f, tri_z), Vec3f(tri_x + 0.4f, -0.2f, tri_z),
                            Vec3f(tri_x, 0.2f, tri_z)};
        s.mesh.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6};
        s.codes.resize(s.mesh.positions.size() * 2);
        for (size_t v = 0; v < s.mesh.positions.size(); ++v) encode(Vec3f(0, 0, 1), &s.codes[v * 2]);
        return s;
    };
    const Shape front = make(-1.5f, -2.4f, 0.8f), back = make(-0.5f, 2.0f, -0.8f);
    const Vec3f front_colour(0.9f, 0.1f, 0.1f), back_colour(0.1f, 0.2f, 0.9f);
    const View cam = View::framing(Vec3f(0.0f), 2.6f, Vec3f(0.0f, 0.0f, 1.0f));
    std::vector<Image> images;
    for (bool front_first : {true, false}) {
        RenderFixture f(160, 120);
        REQUIRE_GL(f);
        Renderer& r = f.renderer();
        for (bool is_front : {front_first, !front_first}) {
            MeshData data = (is_front ? front : back).data();
            data.has_position_box = true;  // one box: the squares' codes decode to the same depth
            data.position_box_min = Vec3f(-2.4f, -1.0f, -0.8f);
            data.position_box_max = Vec3f(2.4f, 1.0f, 0.8f);
            auto id = r.add_model(data, is_front ? "front" : "back");
            ASSERT_TRUE(id);
            r.state(id.value())->color = is_front ? front_colour : back_colour;
            r.state(id.value())->style = Style::Smooth;
            (void)f.draw(cam);  // a frame with the models arrived so far
        }
        images.push_back(f.draw(cam));
        ASSERT_EQ(r.last_frame_stats().models_drawn, 2u);
        EXPECT_EQ(r.last_frame_stats().draw_calls, 1u);  // both in one chunk
    }
    EXPECT_TRUE(images[0].rgba == images[1].rgba);
    const Image& im = images[0];
    auto blue = [&](int x) { return im.at(x, im.height / 2)[2] > im.at(x, im.height / 2)[0]; };
    EXPECT_TRUE(blue(im.width / 2)) << "the overlap shows the model drawn last";
    EXPECT_FALSE(blue(im.width / 2 - im.width / 8)) << "the front square left of it";
}

// A model above kMaxBatchedVertices is drawn alone: the same pixels with
// batching on and off, and no chunk holding a second copy of its vertex codes
// and indices (the renderer's GL bytes equal). A small model beside it still
// draws the same.
TEST(RenderBatch, LargeModelDrawnAloneWithoutAChunkCopy) {
    Shape large;
    large.mesh = test::icosphere(7, 0.9f);  // 163,842 vertices
    ASSERT_GT(large.mesh.positions.size(), kMaxBatchedVertices);
    large.codes.resize(large.mesh.positions.size() * 2);
    for (size_t v = 0; v < large.mesh.positions.size(); ++v)
        encode(glm::normalize(large.mesh.positions[v]), &large.codes[v * 2]);
    const Shape small = make_shape(1);
    std::vector<Image> images;
    std::vector<size_t> gl_bytes;
    for (bool batch : {false, true}) {
        RendererOptions options;
        options.batch = batch;
        RenderFixture f(160, 120, options);
        REQUIRE_GL(f);
        Renderer& r = f.renderer();
        auto a = r.add_model(large.data(), "large");
        auto b = r.add_model(small.data(), "small");
        ASSERT_TRUE(a && b);
        r.state(a.value())->style = Style::Smooth;
        r.state(b.value())->transform = glm::translate(glm::mat4(1.0f), Vec3f(1.5f, 0.0f, 0.0f));
        images.push_back(f.draw(View::framing(Vec3f(0.5f, 0.0f, 0.0f), 2.5f, Vec3f(0.2f, 0.3f, 1.0f))));
        gl_bytes.push_back(r.gpu_bytes());
        ASSERT_EQ(r.last_frame_stats().models_drawn, 2u);
    }
    EXPECT_TRUE(images[0].rgba == images[1].rgba);
    // Batched, only the small model's chunk is added (its codes, slots and stream), not the large one's 5 MiB.
    EXPECT_LT(gl_bytes[1], gl_bytes[0] + 64 * 1024);
}

}  // namespace
}  // namespace body::render
