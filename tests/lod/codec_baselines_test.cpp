// The static-mesh codec baselines beside a .bpm's size (builder/lod/codec_baselines.h):
// sizes that follow the mesh and the normals, below the raw arrays, and Draco
// under meshoptimizer on a smooth mesh (what both codecs are known for).
#include "builder/lod/codec_baselines.h"

#include <gtest/gtest.h>

#include <vector>

#include "builder/lod/bpm_writer.h"
#include "shared/pm/bpm_reader.h"
#include "shared/pm/progressive_mesh.h"
#include "tests/lod/lod_test_util.h"

namespace body {
namespace {

struct Sizes {
    size_t vertices = 0, raw = 0, meshopt = 0, meshopt_no_normals = 0, draco = 0, draco_no_normals = 0;
};

Sizes sizes_of(const Mesh& mesh) {
    const std::vector<Mesh> meshes = {mesh};
    auto bytes = lod::encode_bpm(meshes, {});
    EXPECT_TRUE(bytes.ok());
    auto pms = pm::read_bpm_bytes(*bytes, "test.bpm");
    EXPECT_TRUE(pms.ok() && pms->size() == 1);
    pm::ProgressiveMesh& m = *pms->front();
    m.set_level(m.max_level());
    EXPECT_TRUE(m.has_normals());
    const auto idx = m.indices().first(m.max_triangle_count() * 3);
    const uint16_t* q = m.position_codes().data();
    const uint8_t* oct = m.normal_codes().data();
    Sizes s;
    s.vertices = m.max_vertex_count();
    s.raw = s.vertices * 8 + idx.size() * 4;
    s.meshopt = lod::meshopt_codec_bytes(q, oct, s.vertices, idx.data(), idx.size());
    s.meshopt_no_normals = lod::meshopt_codec_bytes(q, nullptr, s.vertices, idx.data(), idx.size());
    s.draco = lod::draco_codec_bytes(q, oct, s.vertices, idx.data(), idx.size());
    s.draco_no_normals = lod::draco_codec_bytes(q, nullptr, s.vertices, idx.data(), idx.size());
    return s;
}

TEST(CodecBaselines, SizesFollowTheMeshAndTheNormals) {
    const Sizes small = sizes_of(test::icosphere(3)), large = sizes_of(test::icosphere(5));
    for (const Sizes& s : {small, large}) {
        EXPECT_GT(s.meshopt, s.vertices);  // more than a byte a vertex: positions and normals of a sphere
        EXPECT_LT(s.meshopt, s.raw / 2);
        EXPECT_LT(s.meshopt_no_normals, s.meshopt);
        if (!lod::draco_available()) {
            EXPECT_EQ(s.draco, 0u);
            continue;
        }
        EXPECT_GT(s.draco, s.vertices);
        EXPECT_LT(s.draco, s.meshopt);
        EXPECT_LT(s.draco_no_normals, s.draco);
    }
    EXPECT_GT(large.meshopt, 8 * small.meshopt);  // 16x the vertices
    if (lod::draco_available()) {
        EXPECT_GT(large.draco, 8 * small.draco);
    }
}

}  // namespace
}  // namespace body
