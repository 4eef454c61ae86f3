// The contour-stack -> mesh pipeline, written as its stages in order.
//
// References:
//   BodyGen/BodyView thesis, sections 2.3-2.6 (the stage structure).
//   H. Fuchs, Z. M. Kedem, S. P. Uselton, "Optimal surface reconstruction from
//     planar contours", CACM 20(10), 1977 (bands, via tiling/).
//   D. Meyers, S. Skinner, K. Sloan, "Surfaces from contours", ACM TOG 11(3),
//     1992 (the four sub-problems: correspondence, tiling, branching, fitting).
#include "builder/pipeline/build_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>

#include "builder/contours/validate.h"
#include "shared/mesh_intersect.h"

namespace body {
namespace {

// ---------------------------------------------------------------- helpers

struct UnionFind {
    std::vector<uint32_t> parent;
    explicit UnionFind(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    uint32_t find(uint32_t x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    }
    void unite(uint32_t a, uint32_t b) { parent[find(a)] = find(b); }
};

std::string where(const std::string& path, const Contour& c) {
    return path + ": slice " + std::to_string(c.source_slice) + " contour " + std::to_string(c.source_contour);
}

const Vec3 kPalette[] = {{0.85, 0.33, 0.31}, {0.36, 0.62, 0.83}, {0.45, 0.75, 0.40}, {0.93, 0.70, 0.25},
                         {0.65, 0.45, 0.80}, {0.30, 0.75, 0.72}, {0.90, 0.55, 0.70}, {0.60, 0.60, 0.60}};

// ------------------------------------------------- stage 2: structures

struct Ref {
    uint32_t slice, contour;
};

struct Grouping {
    std::vector<StructureInfo> infos;
    std::vector<std::vector<std::vector<uint32_t>>> members;  // structure -> slice -> contour indices
};

Nesting nesting_of(const Slice& slice, const std::vector<uint32_t>& members) {
    std::vector<std::span<const Vec2>> loops;
    for (uint32_t c : members) loops.emplace_back(slice.contours[c].points);
    return compute_nesting(loops);
}

// Labelled contours go to their structure; unlabelled ones are grouped by
// correspondence of their solid contours across slices (holes follow their parent).
Grouping group_structures(const ContourStack& stack, CorrespondenceMethod method) {
    Grouping g;
    g.infos = stack.structures;
    const size_t S = stack.slices.size();
    std::map<std::string, size_t> index;
    for (size_t i = 0; i < g.infos.size(); ++i) index[g.infos[i].id] = i;
    g.members.assign(g.infos.size(), std::vector<std::vector<uint32_t>>(S));

    std::vector<std::vector<uint32_t>> unlabelled(S);
    for (uint32_t s = 0; s < S; ++s)
        for (uint32_t c = 0; c < stack.slices[s].contours.size(); ++c) {
            const Contour& contour = stack.slices[s].contours[c];
            if (contour.structure.empty())
                unlabelled[s].push_back(c);
            else
                g.members[index[contour.structure]][s].push_back(c);
        }

    // Node numbering over all unlabelled contours.
    std::vector<uint32_t> first(S + 1, 0);
    for (size_t s = 0; s < S; ++s) first[s + 1] = first[s] + uint32_t(unlabelled[s].size());
    UnionFind uf(first[S]);
    std::vector<std::vector<uint32_t>> solids(S);  // positions within unlabelled[s]
    for (size_t s = 0; s < S; ++s) {
        Nesting n = nesting_of(stack.slices[s], unlabelled[s]);
        for (uint32_t k = 0; k < unlabelled[s].size(); ++k) {
            if (n.depth[k] % 2 == 0)
                solids[s].push_back(k);
            else if (n.parent[k] >= 0)
                uf.unite(first[s] + k, first[s] + uint32_t(n.parent[k]));
        }
    }
    for (size_t s = 0; s + 1 < S; ++s) {
        std::vector<PolygonSpan> lower, upper;
        for (uint32_t k : solids[s]) lower.emplace_back(stack.slices[s].contours[unlabelled[s][k]].points);
        for (uint32_t k : solids[s + 1]) upper.emplace_back(stack.slices[s + 1].contours[unlabelled[s + 1][k]].points);
        for (const ContourLink& l : correspond_contours(lower, upper, method))
            uf.unite(first[s] + solids[s][l.lower], first[s + 1] + solids[s + 1][l.upper]);
    }
    std::map<uint32_t, size_t> auto_index;  // union-find root -> structure
    for (uint32_t s = 0; s < S; ++s)
        for (uint32_t k = 0; k < unlabelled[s].size(); ++k) {
            const uint32_t root = uf.find(first[s] + k);
            auto [it, inserted] = auto_index.emplace(root, g.infos.size());
            if (inserted) {
                const size_t n = auto_index.size();
                StructureInfo info;
                info.id = "auto_" + std::to_string(n);
                info.name = "structure " + std::to_string(n);
                info.color = kPalette[(n - 1) % (sizeof kPalette / sizeof kPalette[0])];
                g.infos.push_back(info);
                g.members.emplace_back(S);
            }
            g.members[it->second][s].push_back(unlabelled[s][k]);
        }
    return g;
}

// ---------------------------------------------- stage 3: one structure

struct Loop {
    const Contour* source = nullptr;
    std::vector<Vec2> xy;        // solid counter-clockwise, hole clockwise
    std::vector<uint32_t> ids;   // mesh vertices at the slice's z
    int parent = -1, depth = 0;  // nesting within the structure on this slice
    bool linked_up = false, linked_down = false;
    bool flat_caps = false;  // detached from a branch: a dome could reach into the neighbouring band
    int detached = 0;        // +1: the band below was refused (keep below clear), -1: the band above
    bool hole() const { return depth % 2 == 1; }
};

class StructureBuilder {
public:
    StructureBuilder(const ContourStack& stack, const BuildOptions& options, const std::string& path)
        : stack_(stack), options_(options), path_(path) {}

    Status build(const std::vector<std::vector<uint32_t>>& members, size_t& done, size_t total) {
        make_loops(members);
        for (size_t s = 0; s + 1 < loops_.size(); ++s) {
            if (!loops_[s].empty() || !loops_[s + 1].empty()) {
                auto status = connect(s);
                if (!status) return status;
            }
            ++done;
            if (options_.progress) options_.progress(done, total);
        }
        ++done;
        if (options_.progress) options_.progress(done, total);
        return close_ends();
    }

    std::vector<Vec3> positions;
    std::vector<uint32_t> triangles;

private:
    const ContourStack& stack_;
    const BuildOptions& options_;
    const std::string& path_;
    std::vector<std::vector<Loop>> loops_;

    double z(size_t s) const { return stack_.slices[s].z; }

    // Phase A: loops per slice, nested and oriented, with their mesh vertices.
    void make_loops(const std::vector<std::vector<uint32_t>>& members) {
        loops_.assign(stack_.slices.size(), {});
        for (size_t s = 0; s < stack_.slices.size(); ++s) {
            const Slice& slice = stack_.slices[s];
            Nesting n = nesting_of(slice, members[s]);
            for (size_t k = 0; k < members[s].size(); ++k) {
                Loop loop;
                loop.source = &slice.contours[members[s][k]];
                loop.xy = loop.source->points;
                loop.parent = n.parent[k];
                loop.depth = n.depth[k];
                const bool ccw = signed_area2(loop.xy.data(), loop.xy.size()) > 0;
                if (ccw == loop.hole()) std::reverse(loop.xy.begin(), loop.xy.end());
                for (const Vec2& p : loop.xy) {
                    loop.ids.push_back(uint32_t(positions.size()));
                    positions.emplace_back(p.x, p.y, slice.z);
                }
                loops_[s].push_back(std::move(loop));
            }
        }
    }

    // Band between two id loops (same orientation seen from +z).
    Status band(const std::vector<uint32_t>& lower, const std::vector<uint32_t>& upper, const Loop& blame) {
        std::vector<Vec3> a, b;
        for (uint32_t i : lower) a.push_back(positions[i]);
        for (uint32_t i : upper) b.push_back(positions[i]);
        std::vector<uint32_t> local;
        auto status = tile_band(a, b, options_.tiling, local);
        if (!status) return runtime_error(where(path_, *blame.source) + ": tiling failed: " + status.error().message);
        for (uint32_t v : local) triangles.push_back(v < a.size() ? lower[v] : upper[v - a.size()]);
        return ok_status();
    }

    // Vertical prism between two congruent id loops (used for slabs).
    void prism(const std::vector<uint32_t>& lower, const std::vector<uint32_t>& upper) {
        const size_t n = lower.size();
        for (size_t i = 0; i < n; ++i) {
            const size_t j = (i + 1) % n;
            triangles.insert(triangles.end(), {lower[i], lower[j], upper[j]});
            triangles.insert(triangles.end(), {lower[i], upper[j], upper[i]});
        }
    }

    std::vector<uint32_t> lifted_copy(const std::vector<Vec2>& xy, double at) {
        std::vector<uint32_t> ids;
        for (const Vec2& p : xy) {
            ids.push_back(uint32_t(positions.size()));
            positions.emplace_back(p.x, p.y, at);
        }
        return ids;
    }

    // Phase B: correspondence between slices s and s+1, then bands and branches.
    Status connect(size_t s) {
        for (int hole = 0; hole < 2; ++hole) {
            std::vector<uint32_t> lo, up;
            for (uint32_t k = 0; k < loops_[s].size(); ++k)
                if (loops_[s][k].hole() == bool(hole)) lo.push_back(k);
            for (uint32_t k = 0; k < loops_[s + 1].size(); ++k)
                if (loops_[s + 1][k].hole() == bool(hole)) up.push_back(k);
            if (lo.empty() || up.empty()) continue;
            std::vector<PolygonSpan> a, b;
            for (uint32_t k : lo) a.emplace_back(loops_[s][k].xy);
            for (uint32_t k : up) b.emplace_back(loops_[s + 1][k].xy);
            const auto links = correspond_contours(a, b, options_.correspondence);
            UnionFind uf(lo.size() + up.size());
            for (const ContourLink& l : links) uf.unite(l.lower, uint32_t(lo.size()) + l.upper);
            std::map<uint32_t, std::pair<std::vector<uint32_t>, std::vector<uint32_t>>> groups;
            for (const ContourLink& l : links) {
                auto& g = groups[uf.find(l.lower)];
                g.first.push_back(lo[l.lower]);
                g.second.push_back(up[l.upper]);
            }
            for (auto& [root, g] : groups) {
                auto& [gl, gu] = g;
                std::sort(gl.begin(), gl.end());
                gl.erase(std::unique(gl.begin(), gl.end()), gl.end());
                std::sort(gu.begin(), gu.end());
                gu.erase(std::unique(gu.begin(), gu.end()), gu.end());
                for (uint32_t k : gl) loops_[s][k].linked_up = true;
                for (uint32_t k : gu) loops_[s + 1][k].linked_down = true;
                Status status = ok_status();
                if (options_.branching == BranchingMethod::Overlap && gl.size() + gu.size() > 2) {
                    for (const ContourLink& l : links)
                        if (uf.find(l.lower) == root) {
                            status = band(loops_[s][lo[l.lower]].ids, loops_[s + 1][up[l.upper]].ids,
                                          loops_[s][lo[l.lower]]);
                            if (!status) return status;
                        }
                    continue;
                }
                status = connect_group(s, gl, gu, bool(hole));
                if (!status) return status;
            }
        }
        return ok_status();
    }

    Status connect_group(size_t s, const std::vector<uint32_t>& gl, const std::vector<uint32_t>& gu, bool hole) {
        const Loop& first_lower = loops_[s][gl[0]];
        if (gl.size() == 1 && gu.size() == 1) return band(first_lower.ids, loops_[s + 1][gu[0]].ids, first_lower);
        // Constructions in order of faithfulness: the nested region (when it
        // applies), the partition, the regions around the grown hull. The first
        // whose triangles do not cross each other is kept; failing that, the
        // first that could be built at all (still closed, but crossing).
        const bool one_side = gl.size() == 1 || gu.size() == 1;
        const size_t tri0 = triangles.size(), pos0 = positions.size();
        const std::vector<Loop> saved_lower = loops_[s], saved_upper = loops_[s + 1];
        auto roll_back = [&] {
            triangles.resize(tri0);
            positions.resize(pos0);
            loops_[s] = saved_lower;
            loops_[s + 1] = saved_upper;
        };
        int first_built = -1;
        Status first_error = ok_status();
        for (int attempt = 0; attempt < 3; ++attempt) {
            if (!one_side && attempt < 2) continue;
            Status status = attempt == 0   ? connect_nested(s, gl, gu, hole)
                            : attempt == 1 ? connect_partition(s, gl, gu)
                                           : connect_hull(s, gl, gu, hole);
            if (status && count_self_intersections(positions, std::span<const uint32_t>(triangles).subspan(tri0)) == 0)
                return status;
            if (status && first_built < 0) first_built = attempt;
            if (!status && first_error) first_error = status;
            roll_back();
        }
        if (first_built < 0)
            return first_error.ok() ? input_error(where(path_, *first_lower.source) + ": branching failed")
                                    : first_error;
        return first_built == 0   ? connect_nested(s, gl, gu, hole)
               : first_built == 1 ? connect_partition(s, gl, gu)
                                  : connect_hull(s, gl, gu, hole);
    }

    Status connect_nested(size_t s, const std::vector<uint32_t>& gl, const std::vector<uint32_t>& gu, bool hole) {
        if (gl.size() == 1 && nested(s, gl[0], s + 1, gu)) return nested_branch(s, gl[0], s + 1, gu, hole);
        if (gu.size() == 1 && nested(s + 1, gu[0], s, gl)) return nested_branch(s + 1, gu[0], s, gl, hole);
        return input_error("not nested");
    }

    Status connect_partition(size_t s, const std::vector<uint32_t>& gl, const std::vector<uint32_t>& gu) {
        const Loop& first_lower = loops_[s][gl[0]];
        const double zl = z(s), zu = z(s + 1);
        if (gl.size() == 1) {
            const std::vector<uint32_t> kept = detach_interior(s, gl[0], s + 1, gu);
            if (kept.size() == 1) return band(first_lower.ids, loops_[s + 1][kept[0]].ids, first_lower);
            return split(first_lower.ids, loops_[s + 1], kept, 0.5 * (zl + zu), true, first_lower);
        }
        const std::vector<uint32_t> kept = detach_interior(s + 1, gu[0], s, gl);
        if (kept.size() == 1) return band(loops_[s][kept[0]].ids, loops_[s + 1][gu[0]].ids, first_lower);
        return split(loops_[s + 1][gu[0]].ids, loops_[s], kept, 0.5 * (zl + zu), false, first_lower);
    }

    // A mid-slice contour (convex hull of the group) takes N:1 below and 1:M above.
    Status connect_hull(size_t s, const std::vector<uint32_t>& gl, const std::vector<uint32_t>& gu, bool hole) {
        const Loop& first_lower = loops_[s][gl[0]];
        const double zl = z(s), zu = z(s + 1);
        std::vector<Vec2> pts;
        for (uint32_t k : gl) pts.insert(pts.end(), loops_[s][k].xy.begin(), loops_[s][k].xy.end());
        for (uint32_t k : gu) pts.insert(pts.end(), loops_[s + 1][k].xy.begin(), loops_[s + 1][k].xy.end());
        std::vector<Vec2> hull = convex_hull(pts);
        if (hole) std::reverse(hull.begin(), hull.end());  // rings run clockwise around voids
        const double zm = 0.5 * (zl + zu);
        if (without_children(s, gl) && without_children(s + 1, gu)) {
            // The hull grown by 1% around its centre holds every contour strictly
            // inside: a nested region below it and another above.
            Vec2 centre(0.0);
            for (const Vec2& p : hull) centre += p;
            centre /= double(hull.size());
            for (Vec2& p : hull) p = centre + (p - centre) * 1.01;
            const std::vector<uint32_t> mid = lifted_copy(hull, zm);
            std::vector<const Loop*> below, above;
            for (uint32_t k : gl) below.push_back(&loops_[s][k]);
            for (uint32_t k : gu) above.push_back(&loops_[s + 1][k]);
            auto status = nested_region(hull, mid, zm, below, zl, hole, first_lower);
            if (!status) return status;
            return nested_region(hull, mid, zm, above, zu, hole, first_lower);
        }
        std::vector<uint32_t> mid = lifted_copy(hull, zm);
        auto status = split(mid, loops_[s], gl, 0.5 * (zl + zm), false, first_lower);
        if (!status) return status;
        return split(mid, loops_[s + 1], gu, 0.5 * (zm + zu), true, first_lower);
    }

    // Do the branches on slice `bs` lie strictly inside the single loop on slice
    // `ss` (seen from above), with no other loop of the structure inside them or
    // inside the single loop's region on its own slice?
    // (`holes_matter` false: only the containment is asked.)
    bool nested(size_t ss, uint32_t single, size_t bs, const std::vector<uint32_t>& branches,
                bool holes_matter = true) const {
        const Loop& outer = loops_[ss][single];
        for (size_t k = 0; k < loops_[ss].size() && holes_matter; ++k)
            if (loops_[ss][k].parent == int(single)) return false;
        std::vector<std::span<const Vec2>> all{outer.xy};
        for (uint32_t b : branches) {
            for (size_t k = 0; k < loops_[bs].size() && holes_matter; ++k)
                if (loops_[bs][k].parent == int(b)) return false;
            for (const Vec2& p : loops_[bs][b].xy)
                if (!point_in_polygon(p, outer.xy)) return false;
            all.emplace_back(loops_[bs][b].xy);
        }
        return !find_crossing(all).found;
    }

    // When some branches reach outside the single contour (so the nested method
    // does not apply), side branches lying wholly inside it would get a far-away
    // arc of it and a band sweeping across the others; they are detached instead
    // and closed by their own flat cap at their slice (the band towards the
    // other branches stays below that plane there, so nothing crosses). The
    // largest branch is never detached. Returns the branches that stay linked.
    std::vector<uint32_t> detach_interior(size_t ss, uint32_t single, size_t bs,
                                          const std::vector<uint32_t>& branches) {
        uint32_t main = branches[0];
        for (uint32_t b : branches)
            if (std::abs(signed_area2(loops_[bs][b].xy.data(), loops_[bs][b].xy.size())) >
                std::abs(signed_area2(loops_[bs][main].xy.data(), loops_[bs][main].xy.size())))
                main = b;
        std::vector<uint32_t> kept;
        for (uint32_t b : branches) {
            if (b != main && nested(ss, single, bs, {b}, false)) {
                Loop& loop = loops_[bs][b];
                (bs > ss ? loop.linked_down : loop.linked_up) = false;
                loop.flat_caps = true;
                loop.detached = bs > ss ? 1 : -1;
                continue;
            }
            kept.push_back(b);
        }
        return kept;
    }

    // Branches nested inside the single contour: the single contour rises as a
    // vertical wall for a third of the spacing, the branches drop as vertical
    // walls for a third, and the middle third is the planar region between them
    // (single minus branches) triangulated and lifted linearly: a height field
    // over a planar triangulation, so it cannot fold or cross itself.
    Status nested_branch(size_t ss, uint32_t single, size_t bs, const std::vector<uint32_t>& branches, bool hole) {
        const Loop& outer = loops_[ss][single];
        std::vector<const Loop*> inner;
        for (uint32_t b : branches) inner.push_back(&loops_[bs][b]);
        return nested_region(outer.xy, outer.ids, z(ss), inner, z(bs), hole, outer);
    }

    // The construction above for any outer ring (`outer_xy`/`outer_ids` at
    // `z_outer`) and inner loops at `z_inner`.
    Status nested_region(const std::vector<Vec2>& outer_xy, const std::vector<uint32_t>& outer_ids, double z_outer,
                         const std::vector<const Loop*>& inner, double z_inner, bool hole, const Loop& blame) {
        const double z_a = z_outer + (z_inner - z_outer) / 3, z_b = z_outer + 2 * (z_inner - z_outer) / 3;
        const bool outer_below = z_outer < z_inner;
        std::vector<uint32_t> outer_copy = lifted_copy(outer_xy, z_a);
        if (outer_below)
            prism(outer_ids, outer_copy);
        else
            prism(outer_copy, outer_ids);
        std::vector<std::span<const Vec2>> region{outer_xy};
        std::vector<uint32_t> ids(outer_copy);
        for (const Loop* branch : inner) {
            std::vector<uint32_t> copy = lifted_copy(branch->xy, z_b);
            if (outer_below)
                prism(copy, branch->ids);
            else
                prism(branch->ids, copy);
            region.emplace_back(branch->xy);
            ids.insert(ids.end(), copy.begin(), copy.end());
        }
        std::vector<uint32_t> local;
        auto status = triangulate_polygon_with_holes(region, local);
        if (!status) return input_error(where(path_, *blame.source) + ": branching: " + status.error().message);
        // Triangles come out counter-clockwise from +z: right for the roof over a
        // solid that narrows upwards; the floor (outer above) and holes face the other way.
        const bool face_up = outer_below != hole;
        for (size_t t = 0; t < local.size(); t += 3) {
            const uint32_t a = ids[local[t]], b = ids[local[t + 1]], c = ids[local[t + 2]];
            if (face_up)
                triangles.insert(triangles.end(), {a, b, c});
            else
                triangles.insert(triangles.end(), {a, c, b});
        }
        return ok_status();
    }

    // No loop of the structure nested inside any of `members` on slice s.
    bool without_children(size_t s, const std::vector<uint32_t>& members) const {
        for (const Loop& l : loops_[s])
            for (uint32_t m : members)
                if (l.parent == int(m)) return false;
        return true;
    }

    // One id loop against several branch loops: partition, then tile each piece.
    Status split(const std::vector<uint32_t>& single, const std::vector<Loop>& others,
                 const std::vector<uint32_t>& branch_ids, double chord_z, bool single_is_lower, const Loop& blame) {
        std::vector<std::span<const Vec2>> branches;
        for (uint32_t k : branch_ids) branches.emplace_back(others[k].xy);
        auto pieces = partition_contour(single, branches, chord_z, positions);
        if (!pieces) return input_error(where(path_, *blame.source) + ": branching: " + pieces.error().message);
        for (size_t b = 0; b < branch_ids.size(); ++b) {
            const auto& piece = (*pieces)[b];
            const auto& other = others[branch_ids[b]].ids;
            auto status = single_is_lower ? band(piece, other, blame) : band(other, piece, blame);
            if (!status) return status;
        }
        return ok_status();
    }

    static std::vector<Vec2> convex_hull(std::vector<Vec2> p) {
        std::sort(p.begin(), p.end(),
                  [](const Vec2& a, const Vec2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
        p.erase(std::unique(p.begin(), p.end()), p.end());
        if (p.size() < 3) return p;
        std::vector<Vec2> h(2 * p.size());
        size_t k = 0;
        auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
            return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
        };
        for (size_t i = 0; i < p.size(); ++i) {
            while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
            h[k++] = p[i];
        }
        for (size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
            while (k >= t && cross(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
            h[k++] = p[i - 1];
        }
        h.resize(k - 1);
        return h;
    }

    // Spacing to the neighbouring slices (for dome height and slabs).
    double spacing(size_t s, bool up) const {
        const size_t S = stack_.slices.size();
        if (up && s + 1 < S) return z(s + 1) - z(s);
        if (!up && s > 0) return z(s) - z(s - 1);
        if (s + 1 < S) return z(s + 1) - z(s);
        if (s > 0) return z(s) - z(s - 1);
        return 0.0;
    }

    // Phase C: caps where nothing continues, slabs for contours linked to nothing.
    Status close_ends() {
        for (size_t s = 0; s < loops_.size(); ++s) {
            auto& loops = loops_[s];
            if (loops.empty()) continue;
            // Isolated loops become slabs a quarter spacing thick on each side.
            double thick = std::min(spacing(s, true), spacing(s, false));
            if (!(thick > 0)) {
                Aabb box;
                for (const Loop& l : loops)
                    for (const Vec2& p : l.xy) box.extend(Vec3(p, 0.0));
                thick = 0.1 * box.extent();
            }
            std::vector<std::vector<uint32_t>> top(loops.size()), bottom(loops.size());
            for (size_t k = 0; k < loops.size(); ++k) {
                Loop& l = loops[k];
                if (l.linked_up || l.linked_down) continue;
                // A detached branch grows away from the band it was refused (one-sided slab).
                // A loop nested in a continuing one (a hole seen on one slice) stays
                // thin: the bands of its parent pass close by above and below.
                const bool inside_continuing =
                    l.parent >= 0 && (loops[size_t(l.parent)].linked_up || loops[size_t(l.parent)].linked_down);
                const double half = inside_continuing ? 0.05 : 0.25;
                if (l.detached <= 0) {
                    bottom[k] = lifted_copy(l.xy, z(s) - (l.detached ? 2 * half : half) * thick);
                    prism(bottom[k], l.ids);
                } else {
                    bottom[k] = l.ids;
                }
                if (l.detached >= 0) {
                    top[k] = lifted_copy(l.xy, z(s) + (l.detached ? 2 * half : half) * thick);
                    prism(l.ids, top[k]);
                } else {
                    top[k] = l.ids;
                }
            }
            for (int up = 0; up < 2; ++up) {
                // Rings ending in this direction: own rings at z(s), slab rings apart.
                for (int slab = 0; slab < 2; ++slab) {
                    std::vector<bool> in(loops.size(), false);
                    for (size_t k = 0; k < loops.size(); ++k) {
                        const Loop& l = loops[k];
                        const bool isolated = !l.linked_up && !l.linked_down;
                        in[k] = slab ? isolated : (!isolated && !(up ? l.linked_up : l.linked_down));
                    }
                    for (size_t k = 0; k < loops.size(); ++k) {
                        if (!in[k] || (loops[k].parent >= 0 && in[size_t(loops[k].parent)])) continue;
                        std::vector<std::span<const Vec2>> region{loops[k].xy};
                        std::vector<std::span<const uint32_t>> ids{slab ? (up ? top[k] : bottom[k]) : loops[k].ids};
                        const double at = positions[ids[0][0]].z;
                        const double dome = slab ? 0.8 * std::abs(at - z(s)) : 0.45 * spacing(s, bool(up));
                        for (size_t c = 0; c < loops.size(); ++c)
                            if (in[c] && loops[c].parent == int(k)) {
                                region.emplace_back(loops[c].xy);
                                ids.emplace_back(slab ? (up ? top[c] : bottom[c]) : loops[c].ids);
                            }
                        // A region whose outer loop is a hole faces the other way.
                        const bool face_up = bool(up) != loops[k].hole();
                        const CapStyle style =
                            loops[k].flat_caps && options_.caps == CapStyle::Dome ? CapStyle::Flat : options_.caps;
                        auto status = build_cap(region, ids, at, face_up, style, dome, positions, triangles);
                        if (!status) return input_error(where(path_, *loops[k].source) + ": " + status.error().message);
                    }
                }
            }
        }
        return ok_status();
    }
};

}  // namespace

Result<std::vector<StructureMesh>> build_structures(const ContourStack& input, const BuildOptions& options,
                                                    const std::string& source_path) {
    // Stage 1: validation and repair.
    ContourStack stack = input;
    std::vector<std::string> warnings;
    auto valid = validate_contour_stack(stack, source_path, warnings);
    if (!valid) return valid.error();  // the error is the one line to show; repairs do not matter then
    if (options.warning)
        for (const auto& w : warnings) options.warning(w);

    // Stage 2: structures (labels, or correspondence for unlabelled contours).
    Grouping grouping = group_structures(stack, options.correspondence);

    // Stage 3: one mesh per structure.
    std::vector<StructureMesh> out;
    size_t total = 0, done = 0;
    for (const auto& m : grouping.members)
        if (std::any_of(m.begin(), m.end(), [](const auto& v) { return !v.empty(); })) total += stack.slices.size();
    for (size_t i = 0; i < grouping.infos.size(); ++i) {
        const auto& members = grouping.members[i];
        size_t contours = 0;
        for (const auto& v : members) contours += v.size();
        if (contours == 0) continue;
        const auto start = std::chrono::steady_clock::now();
        StructureBuilder builder(stack, options, source_path);
        auto status = builder.build(members, done, total);
        if (!status) return status.error();
        StructureMesh sm;
        sm.id = grouping.infos[i].id;
        sm.contours = contours;
        sm.mesh.name = grouping.infos[i].name;
        sm.mesh.color = grouping.infos[i].color;
        sm.mesh.positions = std::move(builder.positions);
        sm.mesh.indices = std::move(builder.triangles);
        const MeshTopology topo = analyze_topology(sm.mesh.positions, sm.mesh.indices);
        sm.triangles = sm.mesh.triangle_count();
        sm.volume = mesh_volume(sm.mesh.positions, sm.mesh.indices);
        sm.area = mesh_area(sm.mesh.positions, sm.mesh.indices);
        sm.closed_manifold = topo.closed_manifold();
        sm.genus = topo.genus();
        sm.components = topo.components;
        sm.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        out.push_back(std::move(sm));
    }
    return out;
}

}  // namespace body
