// See split_order.h. Phases: rounds (replay the splits in their order, tracking
// each vertex's faces, and give each split the round after the last split of its
// batch sharing a face with it), order (rounds, each by parent number), relabel.
#include "builder/lod/split_order.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "shared/pm/draw_order.h"

namespace body::lod {

namespace {

constexpr uint32_t kNone = UINT32_MAX;

// The faces around each vertex (a face once per corner naming the vertex), in 64-byte
// blocks: block v is vertex v's first, overflow blocks follow on through `next`. One
// cache line for most vertices, and no allocation per vertex or per face moved.
// Unordered: removal moves the last face into the hole.
class Stars {
public:
    explicit Stars(size_t vertices) {
        blocks_.reserve(vertices + vertices / 4);
        blocks_.resize(vertices);
    }
    void add(uint32_t v, uint32_t f) {
        uint32_t b = v, k = blocks_[v].count++;
        for (; k >= kItems; k -= kItems) {
            if (blocks_[b].next == kNone) {
                blocks_[b].next = uint32_t(blocks_.size());
                blocks_.emplace_back();
            }
            b = blocks_[b].next;
        }
        blocks_[b].face[k] = f;
    }
    // Removes one occurrence of f (none there: nothing).
    void remove(uint32_t v, uint32_t f) {
        uint32_t* hole = nullptr;
        uint32_t* last = nullptr;
        for (uint32_t b = v, left = blocks_[v].count; left > 0; b = blocks_[b].next) {
            const uint32_t m = std::min(left, kItems);
            uint32_t* face = blocks_[b].face;
            for (uint32_t i = 0; i < m && !hole; ++i)
                if (face[i] == f) hole = &face[i];
            left -= m;
            if (left == 0) last = &face[m - 1];
        }
        if (!hole) return;
        *hole = *last;
        --blocks_[v].count;
    }
    template <class F>
    void for_each(uint32_t v, F&& fn) const {
        for (uint32_t b = v, left = blocks_[v].count; left > 0; b = blocks_[b].next) {
            const uint32_t m = std::min(left, kItems);
            for (uint32_t i = 0; i < m; ++i) fn(blocks_[b].face[i]);
            left -= m;
        }
    }

private:
    static constexpr uint32_t kItems = 14;
    struct alignas(64) Block {
        uint32_t count = 0;  // (in a vertex's first block)
        uint32_t face[kItems];
        uint32_t next = kNone;
    };
    std::vector<Block> blocks_;
};

// Per split, its round inside its batch: two splits that touch a common face (one
// around its parent, or one it adds) keep their order; splits that share no face
// change disjoint parts of the mesh, so they commute. (Only each star's set matters:
// a round is a maximum over the faces, and each face touched gets the same `last`.)
std::vector<uint32_t> rounds(const ProgressiveBuild& pm, const std::vector<uint32_t>& bounds,
                             const std::vector<uint32_t>& first_face) {
    const size_t base = pm.base_vertices, n = pm.splits.size();
    std::vector<uint32_t> idx(pm.indices.begin(), pm.indices.end());
    Stars star(base + n);
    for (uint32_t f = 0; f < pm.base_faces; ++f)
        for (int k = 0; k < 3; ++k) star.add(idx[size_t(f) * 3 + k], f);
    std::vector<uint32_t> last(idx.size() / 3, kNone), round(n, 0);
    size_t lo = 0;
    for (uint32_t hi : bounds) {
        for (size_t j = lo; j < hi; ++j) {
            const uint32_t p = pm.splits[j].parent, c = uint32_t(base + j);
            uint32_t r = 0;
            auto after = [&](uint32_t f) {
                if (last[f] != kNone && last[f] >= lo) r = std::max(r, round[last[f]] + 1);
                last[f] = uint32_t(j);
            };
            star.for_each(p, after);
            for (uint32_t f = first_face[j]; f < first_face[j + 1]; ++f) after(f);
            round[j] = r;
            // Apply the split: patched faces move from the parent's star to the child's.
            for (uint32_t i = pm.patch_begin[j]; i < pm.patch_begin[j + 1]; ++i) {
                const uint32_t f = pm.patch_faces[i];
                for (int k = 0; k < 3; ++k)
                    if (idx[size_t(f) * 3 + k] == p) idx[size_t(f) * 3 + k] = c;
                star.remove(p, f);
                star.add(c, f);
            }
            for (uint32_t f = first_face[j]; f < first_face[j + 1]; ++f)
                for (int k = 0; k < 3; ++k) star.add(idx[size_t(f) * 3 + k], f);
        }
        lo = hi;
    }
    return round;
}

// The new order (order[i] = the old split i-th): per batch, round by round, each
// round by its parents' new numbers (known: a parent born in the batch is an
// earlier round's child).
std::vector<uint32_t> new_order(const ProgressiveBuild& pm, const std::vector<uint32_t>& bounds,
                                const std::vector<uint32_t>& round, std::vector<uint32_t>& vmap) {
    const size_t base = pm.base_vertices, n = pm.splits.size();
    vmap.resize(base + n);
    for (size_t v = 0; v < base; ++v) vmap[v] = uint32_t(v);
    std::vector<uint32_t> order;
    order.reserve(n);
    std::vector<uint32_t> batch;
    size_t lo = 0;
    for (uint32_t hi : bounds) {
        batch.clear();
        for (size_t j = lo; j < hi; ++j) batch.push_back(uint32_t(j));
        std::stable_sort(batch.begin(), batch.end(), [&](uint32_t a, uint32_t b) { return round[a] < round[b]; });
        for (size_t i = 0; i < batch.size();) {
            size_t e = i;
            while (e < batch.size() && round[batch[e]] == round[batch[i]]) ++e;
            std::sort(batch.begin() + ptrdiff_t(i), batch.begin() + ptrdiff_t(e), [&](uint32_t a, uint32_t b) {
                const uint32_t pa = vmap[pm.splits[a].parent], pb = vmap[pm.splits[b].parent];
                return pa != pb ? pa < pb : a < b;
            });
            for (size_t t = i; t < e; ++t) {
                vmap[base + batch[t]] = uint32_t(base + order.size());
                order.push_back(batch[t]);
            }
            i = e;
        }
        lo = hi;
    }
    return order;
}

}  // namespace

void order_splits_in_batches(ProgressiveBuild& pm) {
    const size_t base = pm.base_vertices, n = pm.splits.size();
    if (n < 2) return;
    std::vector<uint32_t> first_face(n + 1);
    first_face[0] = uint32_t(pm.base_faces);
    for (size_t j = 0; j < n; ++j) first_face[j + 1] = first_face[j] + pm.splits[j].face_count;
    const std::vector<uint32_t> bounds = pm::batch_levels(base, n);
    const std::vector<uint32_t> round = rounds(pm, bounds, first_face);
    std::vector<uint32_t> vmap;
    const std::vector<uint32_t> order = new_order(pm, bounds, round, vmap);

    ProgressiveBuild out;
    out.base_vertices = base;
    out.base_faces = pm.base_faces;
    out.positions.resize(pm.positions.size());
    out.normals.resize(pm.normals.size());
    for (size_t v = 0; v < pm.positions.size(); ++v) out.positions[vmap[v]] = pm.positions[v];
    for (size_t v = 0; v < pm.normals.size(); ++v) out.normals[vmap[v]] = pm.normals[v];
    std::vector<uint32_t> fmap(pm.indices.size() / 3);
    for (uint32_t f = 0; f < pm.base_faces; ++f) fmap[f] = f;
    uint32_t next = uint32_t(pm.base_faces);
    for (uint32_t j : order)
        for (uint32_t f = first_face[j]; f < first_face[j + 1]; ++f) fmap[f] = next++;
    out.indices.resize(pm.indices.size());
    for (size_t f = 0; f < fmap.size(); ++f)
        for (int k = 0; k < 3; ++k) out.indices[size_t(fmap[f]) * 3 + k] = vmap[pm.indices[f * 3 + k]];
    out.splits.resize(n);
    out.patch_begin.resize(n + 1);
    out.patch_faces.resize(pm.patch_faces.size());
    uint32_t at = 0;
    for (size_t i = 0; i < n; ++i) {
        const uint32_t j = order[i];
        out.splits[i] = pm.splits[j];
        out.splits[i].parent = vmap[pm.splits[j].parent];
        out.patch_begin[i] = at;
        for (uint32_t t = pm.patch_begin[j]; t < pm.patch_begin[j + 1]; ++t)
            out.patch_faces[at++] = fmap[pm.patch_faces[t]];
    }
    out.patch_begin[n] = at;
    // A level's error: the largest of the splits still to come (non-increasing).
    for (size_t i = n - 1; i-- > 0;) out.splits[i].error = std::max(out.splits[i].error, out.splits[i + 1].error);
    pm = std::move(out);
}

}  // namespace body::lod
