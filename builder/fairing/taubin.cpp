// Taubin lambda|mu surface fairing (see fairing.h).
//
// Reference:
//   G. Taubin, "A signal processing approach to fair surface design", SIGGRAPH 1995.
//
// Pipeline (static phases, public entry at the bottom):
//   build_neighbours  unique edge neighbours per vertex (CSR), boundary vertices pinned
//   umbrella_step     p += factor x (mean of neighbours - p), Jacobi style (reads old, writes new)
//   undo_new_intersections  puts back the vertices of triangle pairs that smoothing made intersect
#include <algorithm>
#include <cassert>
#include <utility>
#include <vector>

#include "builder/fairing/fairing.h"
#include "shared/mesh_intersect.h"

namespace body {
namespace {

// Neighbours of v: neighbours[offsets[v] .. offsets[v + 1]), each once however many
// faces share the edge. pinned[v]: v lies on a boundary edge.
void build_neighbours(std::span<const uint32_t> indices, size_t n, std::vector<uint32_t>& offsets,
                      std::vector<uint32_t>& neighbours, std::vector<uint8_t>& pinned) {
    // Directed half-edges a -> b from every face; an undirected edge seen once is a
    // boundary edge (twice, in opposite directions, an interior one).
    std::vector<uint64_t> edges;
    edges.reserve(indices.size() * 2);
    for (size_t f = 0; f + 2 < indices.size(); f += 3)
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = indices[f + size_t(k)], b = indices[f + size_t((k + 1) % 3)];
            if (a == b) continue;
            edges.push_back(uint64_t(a) << 32 | b);
            edges.push_back(uint64_t(b) << 32 | a);
        }
    std::sort(edges.begin(), edges.end());
    pinned.assign(n, 0);
    offsets.assign(n + 1, 0);
    neighbours.clear();
    for (size_t i = 0; i < edges.size();) {
        size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        const uint32_t a = uint32_t(edges[i] >> 32), b = uint32_t(edges[i]);
        if (j - i == 1) pinned[a] = pinned[b] = 1;  // one face on this edge
        neighbours.push_back(b);
        ++offsets[a + 1];
        i = j;
    }
    for (size_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
}

void umbrella_step(std::span<const Vec3> from, std::span<Vec3> to, const std::vector<uint32_t>& offsets,
                   const std::vector<uint32_t>& neighbours, const std::vector<uint8_t>& pinned, double factor) {
    for (size_t v = 0; v < from.size(); ++v) {
        const uint32_t begin = offsets[v], end = offsets[v + 1];
        if (pinned[v] || begin == end) {
            to[v] = from[v];
            continue;
        }
        Vec3 mean(0.0);
        for (uint32_t i = begin; i < end; ++i) mean += from[neighbours[i]];
        mean /= double(end - begin);
        to[v] = from[v] + factor * (mean - from[v]);
    }
}

// A thin part (a gyrus, a narrow duct) can fold through itself or its neighbour
// while it is smoothed. Every pair of triangles that intersects now but did not
// in the input gets its vertices put back where the input had them. A vertex put
// back can meet a smoothed neighbour, so this repeats; a pair whose six vertices are
// all back is an input pair, so each round puts back at least one vertex or ends.
// Only pairs with a triangle off its input position are counted, and the
// input is asked only about the pairs found. After kRounds the whole mesh
// goes back (never seen on the atlas). Returns the number of vertices put back.
size_t undo_new_intersections(std::span<Vec3> positions, std::span<const Vec3> input,
                              std::span<const uint32_t> indices) {
    constexpr int kRounds = 32;
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    std::vector<uint8_t> restored(positions.size(), 0), moved(indices.size() / 3);
    size_t count = 0;
    for (int round = 0; round < kRounds; ++round) {
        for (size_t t = 0; t < moved.size(); ++t) {
            moved[t] = 0;
            for (int k = 0; k < 3; ++k)
                moved[t] |= positions[indices[3 * t + size_t(k)]] != input[indices[3 * t + size_t(k)]];
        }
        (void)count_self_intersections_of(positions, indices, moved, 0, &pairs);
        const std::vector<uint8_t> met_before = triangle_pairs_meet(input, indices, pairs);
        bool changed = false;
        for (size_t p = 0; p < pairs.size(); ++p) {
            if (met_before[p]) continue;
            for (const uint32_t t : {pairs[p].first, pairs[p].second})
                for (int k = 0; k < 3; ++k) {
                    const uint32_t v = indices[size_t(t) * 3 + size_t(k)];
                    if (restored[v]) continue;
                    restored[v] = 1;
                    ++count;
                    changed = positions[v] != input[v] || changed;
                    positions[v] = input[v];
                }
        }
        if (!changed) return count;
    }
    std::copy(input.begin(), input.end(), positions.begin());
    return positions.size();
}

}  // namespace

size_t taubin_smooth(std::span<Vec3> positions, std::span<const uint32_t> indices, const FairingOptions& options) {
    assert(options.lambda > 0.0 && options.lambda < 1.0);
    assert(options.pass_band > 0.0 && options.pass_band < 1.0 / options.lambda);
    if (options.iterations <= 0 || positions.empty()) return 0;
    const std::vector<Vec3> input(positions.begin(), positions.end());
    const size_t n = positions.size();
    std::vector<uint32_t> offsets, neighbours;
    std::vector<uint8_t> pinned;
    build_neighbours(indices, n, offsets, neighbours, pinned);
    std::vector<Vec3> other(n);
    const double mu = 1.0 / (options.pass_band - 1.0 / options.lambda);
    for (int it = 0; it < options.iterations; ++it) {
        umbrella_step(positions, other, offsets, neighbours, pinned, options.lambda);
        umbrella_step(other, positions, offsets, neighbours, pinned, mu);
    }
    return undo_new_intersections(positions, input, indices);
}

}  // namespace body
