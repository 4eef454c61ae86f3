#pragma once
// The progressive-mesh guarantee checked on a real mesh's levels: closed 2-manifold
// of the input's genus and components, not inside out, no fold worse than the input's,
// and the stored error bounding the measured distance to the input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "builder/lod/hausdorff.h"
#include "shared/mesh.h"
#include "shared/pm/progressive_mesh.h"
#include "tests/lod/lod_test_util.h"

namespace body::test {

struct SampledLevels {
    int levels = 0;            // levels checked
    double worst_ratio = 0.0;  // largest measured / (stored error + quantization bound)
};

// Checks `m`'s levels at 22 ratios from 1/128 to 1 against `input`, the mesh it was
// built from (a closed 2-manifold); the Hausdorff distance at every fourth ratio.
inline SampledLevels expect_sampled_levels_within_stored_error(pm::ProgressiveMesh& m, const Mesh& input) {
    const MeshTopology expected = analyze_topology(input.positions, input.indices);
    const double input_volume = mesh_volume(input.positions, input.indices);
    // The input's own near back-to-back neighbours bound what a level may show (0.01:
    // quantization turns those near-degenerate normals a little).
    const double input_fold = std::min(-0.95, min_adjacent_normal_cosine(input.positions, input.indices) - 0.01);
    SampledLevels out;
    for (int i = 0; i < 22; ++i) {
        const double r = std::pow(2.0, -7.0 + 7.0 * i / 21.0);
        m.set_level(m.level_for_triangles(size_t(r * double(m.max_triangle_count()))));
        std::vector<Vec3> pos;
        for (size_t v = 0; v < m.vertex_count(); ++v) pos.push_back(Vec3(m.position(v)));
        std::vector<uint32_t> idx(m.indices().begin(), m.indices().begin() + ptrdiff_t(m.triangle_count() * 3));
        const MeshTopology t = analyze_topology(pos, idx);
        EXPECT_TRUE(t.closed_manifold()) << "level " << m.level() << ": boundary " << t.boundary_edges
                                         << " non-manifold " << t.nonmanifold_edges << " misoriented "
                                         << t.misoriented_edges << " degenerate " << t.degenerate_triangles;
        EXPECT_EQ(t.genus(), expected.genus()) << "level " << m.level();
        EXPECT_EQ(t.components, expected.components) << "level " << m.level();
        EXPECT_GT(mesh_volume(pos, idx) * input_volume, 0.0) << "level " << m.level() << " turned inside out";
        EXPECT_GE(min_adjacent_normal_cosine(pos, idx), input_fold) << "fold at level " << m.level();
        if (i % 4 == 0) {
            const double measured = lod::symmetric_hausdorff(pos, idx, input.positions, input.indices);
            const double stored = m.error_at(m.level()) + m.quantization_bound();
            out.worst_ratio = std::max(out.worst_ratio, measured / stored);
            EXPECT_LE(measured, stored) << "level " << m.level() << " triangles " << m.triangle_count();
        }
        ++out.levels;
    }
    return out;
}

}  // namespace body::test
