// Taubin smoothing (builder/fairing/): removes terraces while a sphere keeps its volume, keeps
// connectivity and open rims, and does nothing with zero iterations.
#include "builder/fairing/fairing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "shared/mesh.h"
#include "tests/common/test_meshes.h"

namespace body {
namespace {

// A unit sphere whose latitude rings alternate between 0.94 and 1.06 of the
// radius: a terraced surface like a stack of slices.
Mesh terraced_sphere() {
    Mesh m = test::uv_sphere(24, 48);
    for (size_t v = 1; v + 1 < m.positions.size(); ++v) {
        const size_t ring = (v - 1) / 48;
        m.positions[v] *= ring % 2 ? 1.06 : 0.94;
    }
    return m;
}

double rms_radius_error(const Mesh& m) {
    double sum = 0.0;
    for (const Vec3& p : m.positions) sum += (glm::length(p) - 1.0) * (glm::length(p) - 1.0);
    return std::sqrt(sum / double(m.positions.size()));
}

TEST(Fairing, TerracesDecayWithoutShrinking) {
    Mesh m = terraced_sphere();
    const double before = rms_radius_error(m), volume = mesh_volume(m.positions, m.indices);
    FairingOptions o;
    o.iterations = 10;
    EXPECT_EQ(taubin_smooth(m.positions, m.indices, o), 0u);  // nothing to put back on a sphere
    const double after = rms_radius_error(m);
    EXPECT_LT(after, 0.35 * before) << before << " -> " << after;
    EXPECT_NEAR(mesh_volume(m.positions, m.indices), volume, 0.03 * volume);
    EXPECT_TRUE(analyze_topology(m.positions, m.indices).closed_manifold());
}

TEST(Fairing, ThePlainLaplacianShrinksWhereTaubinDoesNot) {
    // The mu step is what keeps the volume: the same number of lambda steps
    // alone (the umbrella flow, written out here) shrink the sphere.
    Mesh taubin = terraced_sphere(), laplace = terraced_sphere();
    const double volume = mesh_volume(taubin.positions, taubin.indices);
    FairingOptions o;
    o.iterations = 30;
    taubin_smooth(taubin.positions, taubin.indices, o);
    std::vector<std::set<uint32_t>> ring(laplace.positions.size());
    for (size_t f = 0; f < laplace.indices.size(); f += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = laplace.indices[f + size_t(k)], b = laplace.indices[f + size_t((k + 1) % 3)];
            ring[a].insert(b);
            ring[b].insert(a);
        }
    for (int it = 0; it < 2 * o.iterations; ++it) {
        std::vector<Vec3> next = laplace.positions;
        for (size_t v = 0; v < next.size(); ++v) {
            Vec3 mean(0.0);
            for (const uint32_t w : ring[v]) mean += laplace.positions[w];
            next[v] += o.lambda * (mean / double(ring[v].size()) - laplace.positions[v]);
        }
        laplace.positions = next;
    }
    EXPECT_NEAR(mesh_volume(taubin.positions, taubin.indices), volume, 0.03 * volume);
    EXPECT_LT(mesh_volume(laplace.positions, laplace.indices), 0.9 * volume);
}

TEST(Fairing, ZeroIterationsLeaveTheMeshAsItIs) {
    Mesh m = terraced_sphere();
    const std::vector<Vec3> copy = m.positions;
    EXPECT_EQ(taubin_smooth(m.positions, m.indices, FairingOptions{}), 0u);
    EXPECT_EQ(m.positions, copy);
}

TEST(Fairing, OpenRimsStayWhereTheyAre) {
    // The upper hemisphere only: its equator is a boundary.
    Mesh m = terraced_sphere();
    std::vector<uint32_t> upper;
    for (size_t f = 0; f < m.indices.size(); f += 3)
        if (m.positions[m.indices[f]].z >= -1e-9 && m.positions[m.indices[f + 1]].z >= -1e-9 &&
            m.positions[m.indices[f + 2]].z >= -1e-9)
            upper.insert(upper.end(), {m.indices[f], m.indices[f + 1], m.indices[f + 2]});
    m.indices = upper;
    const MeshTopology topo = analyze_topology(m.positions, m.indices);
    ASSERT_GT(topo.boundary_edges, 0u);
    const std::vector<Vec3> copy = m.positions;
    FairingOptions o;
    o.iterations = 10;
    taubin_smooth(m.positions, m.indices, o);
    size_t rim = 0, moved_inside = 0;
    for (size_t v = 0; v < copy.size(); ++v) {
        if (std::abs(copy[v].z) < 1e-9) {
            ++rim;
            EXPECT_EQ(m.positions[v], copy[v]) << v;
        } else if (copy[v].z > 0.0 && m.positions[v] != copy[v]) {
            ++moved_inside;
        }
    }
    EXPECT_EQ(rim, 48u);
    EXPECT_GT(moved_inside, 100u);
}

}  // namespace
}  // namespace body
