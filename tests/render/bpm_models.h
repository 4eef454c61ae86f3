#pragma once
// Progressive models for the render tests: a mesh or a generated torus
// encoded as a .bpm in memory (default LodOptions), and a kiosk ModelSource
// reading such bytes. A failure is reported as a test failure (empty bytes).
#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "builder/lod/bpm_writer.h"
#include "kiosk/scene/model_source.h"
#include "shared/pm/bpm_reader.h"
#include "tests/render/render_fixture.h"

namespace body::test {

inline std::vector<uint8_t> bpm_of(const Mesh& mesh) {
    const std::vector<Mesh> meshes = {mesh};
    auto bytes = lod::encode_bpm(meshes, {});
    EXPECT_TRUE(bytes.ok()) << (bytes.ok() ? "" : bytes.error().message);
    return bytes.ok() ? *bytes : std::vector<uint8_t>{};
}

// test::torus(rings, segments, 0.7, 0.3) as a .bpm.
inline std::vector<uint8_t> torus_bpm(int rings, int segments) {
    const GenMesh t = torus(rings, segments, 0.7f, 0.3f);
    Mesh mesh;
    for (const Vec3f& p : t.positions) mesh.positions.emplace_back(p);
    mesh.indices = t.indices;
    return bpm_of(mesh);
}

// The one structure of `bytes` (named `name` in messages) as the kiosk holds it.
inline kiosk::ModelSource source_of(const std::vector<uint8_t>& bytes, const char* name) {
    auto meshes = pm::read_bpm_bytes(bytes, name);
    EXPECT_TRUE(meshes.ok() && meshes->size() == 1);
    return kiosk::ModelSource(std::move(meshes->front()));
}

}  // namespace body::test
