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
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <mutex>
#include <numeric>
#include <optional>
#include <thread>

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

// Boundary of the union of `loops` (xy), grown by one to two cells of a grid
// of spacing `cell` and with its holes filled: a simple counter-clockwise ring
// holding every loop strictly inside (at least half a cell away). Marching
// squares over the cell centres of the grown, hole-free, saddle-free mask; runs
// of collinear steps are merged. Empty when the union is not one piece.
std::vector<Vec2> union_ring(const std::vector<std::span<const Vec2>>& loops, double cell) {
    Aabb box;
    for (const auto& l : loops)
        for (const Vec2& p : l) box.extend(Vec3(p, 0.0));
    if (box.empty() || !(cell > 0)) return {};
    const Vec2 lo(box.min), hi(box.max);
    while ((hi.x - lo.x) / cell * ((hi.y - lo.y) / cell) > 4e6) cell *= 1.5;
    const Vec2 origin = lo - Vec2(4 * cell);
    const long nx = long(std::ceil((hi.x - lo.x) / cell)) + 8, ny = long(std::ceil((hi.y - lo.y) / cell)) + 8;
    std::vector<uint8_t> mask(size_t(nx * ny), 0);
    auto at = [&](long i, long j) -> uint8_t& { return mask[size_t(j * nx + i)]; };
    // Interiors by scanlines through the cell centres (even-odd per loop).
    std::vector<double> xs;
    for (long j = 0; j < ny; ++j) {
        const double y = origin.y + (double(j) + 0.5) * cell;
        for (const auto& l : loops) {
            xs.clear();
            for (size_t k = 0; k < l.size(); ++k) {
                const Vec2 a = l[k], b = l[(k + 1) % l.size()];
                if ((a.y <= y) != (b.y <= y)) xs.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
            }
            std::sort(xs.begin(), xs.end());
            for (size_t k = 0; k + 1 < xs.size(); k += 2) {
                const long i0 = std::max(0L, long(std::ceil((xs[k] - origin.x) / cell - 0.5)));
                const long i1 = std::min(nx - 1, long(std::floor((xs[k + 1] - origin.x) / cell - 0.5)));
                for (long i = i0; i <= i1; ++i) at(i, j) = 1;
            }
        }
    }
    // Cells the loops pass through (thin parts have no cell centre inside).
    for (const auto& l : loops)
        for (size_t k = 0; k < l.size(); ++k) {
            const Vec2 a = l[k], b = l[(k + 1) % l.size()];
            const int steps = 1 + int(std::ceil(4 * glm::length(b - a) / cell));
            for (int t = 0; t <= steps; ++t) {
                const Vec2 p = a + (b - a) * (double(t) / steps);
                at(long((p.x - origin.x) / cell), long((p.y - origin.y) / cell)) = 1;
            }
        }
    // Grow by one cell (8-neighbourhood).
    std::vector<uint8_t> grown(mask.size(), 0);
    for (long j = 1; j + 1 < ny; ++j)
        for (long i = 1; i + 1 < nx; ++i)
            for (long dj = -1; dj <= 1; ++dj)
                for (long di = -1; di <= 1; ++di)
                    if (at(i + di, j + dj)) grown[size_t(j * nx + i)] = 1;
    mask.swap(grown);
    // Fill holes and diagonal-only contacts until neither is left.
    for (bool changed = true; changed;) {
        changed = false;
        std::vector<uint8_t> outside(mask.size(), 0);
        std::vector<long> stack{0};
        outside[0] = 1;
        while (!stack.empty()) {
            const long c = stack.back();
            stack.pop_back();
            const long i = c % nx, j = c / nx;
            const long next[4][2] = {{i - 1, j}, {i + 1, j}, {i, j - 1}, {i, j + 1}};
            for (const auto& q : next) {
                if (q[0] < 0 || q[1] < 0 || q[0] >= nx || q[1] >= ny) continue;
                const long d = q[1] * nx + q[0];
                if (!mask[size_t(d)] && !outside[size_t(d)]) outside[size_t(d)] = 1, stack.push_back(d);
            }
        }
        for (size_t c = 0; c < mask.size(); ++c)
            if (!mask[c] && !outside[c]) mask[c] = 1, changed = true;
        for (long j = 0; j + 1 < ny; ++j)
            for (long i = 0; i + 1 < nx; ++i) {
                const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
                if (a == c && b == d && a != b)
                    at(i, j) = at(i + 1, j) = at(i + 1, j + 1) = at(i, j + 1) = 1, changed = true;
            }
    }
    // Marching squares: per block one directed step, from the side where the
    // counter-clockwise walk round the block leaves the mask to where it enters.
    // Nodes on doubled integer coordinates: horizontal side (i,j)-(i+1,j) at
    // (2i+2, 2j+1), vertical side (i,j)-(i,j+1) at (2i+1, 2j+2).
    auto h_side = [&](long i, long j) { return 2 * (j * nx + i); };
    auto v_side = [&](long i, long j) { return 2 * (j * nx + i) + 1; };
    std::map<long, long> next;
    for (long j = 0; j + 1 < ny; ++j)
        for (long i = 0; i + 1 < nx; ++i) {
            const int v[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
            const long side[4] = {h_side(i, j), v_side(i + 1, j), h_side(i, j + 1), v_side(i, j)};
            long exit = -1, entry = -1;
            for (int k = 0; k < 4; ++k) {
                if (v[k] && !v[(k + 1) % 4]) exit = side[k];
                if (!v[k] && v[(k + 1) % 4]) entry = side[k];
            }
            if (exit >= 0 && entry >= 0) next[exit] = entry;
        }
    if (next.empty()) return {};
    auto node = [&](long key) {
        const long c = key / 2, i = c % nx, j = c / nx;
        return key % 2 == 0 ? std::pair<long, long>{2 * i + 2, 2 * j + 1} : std::pair<long, long>{2 * i + 1, 2 * j + 2};
    };
    std::vector<std::pair<long, long>> ring;
    const long start = next.begin()->first;
    for (long key = start;;) {
        ring.push_back(node(key));
        auto it = next.find(key);
        if (it == next.end()) return {};
        key = it->second;
        if (key == start) break;
        if (ring.size() > next.size()) return {};
    }
    if (ring.size() != next.size()) return {};  // more than one piece
    std::vector<Vec2> out;
    const size_t n = ring.size();
    for (size_t k = 0; k < n; ++k) {
        const auto& p = ring[(k + n - 1) % n];
        const auto& q = ring[k];
        const auto& r = ring[(k + 1) % n];
        if ((q.first - p.first) * (r.second - q.second) == (q.second - p.second) * (r.first - q.first)) continue;
        out.push_back(origin + Vec2(double(q.first), double(q.second)) * (0.5 * cell));
    }
    return out;
}

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

    // `advance` is called once per slice (progress).
    Status build(const std::vector<std::vector<uint32_t>>& members, const std::function<void()>& advance) {
        make_loops(members);
        for (size_t s = 0; s + 1 < loops_.size(); ++s) {
            if (!loops_[s].empty() || !loops_[s + 1].empty()) {
                auto status = connect(s);
                if (!status) return status;
            }
            advance();
        }
        advance();
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
        if (gl.size() == 1 && gu.size() == 1) {
            if (!hole) {
                auto status = connect_open_holes(s, gl[0], gu[0]);
                if (!status || *status) return status ? ok_status() : Status(status.error());
            }
            return band(first_lower.ids, loops_[s + 1][gu[0]].ids, first_lower);
        }
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
        auto construct = [&](int method) {
            switch (method) {
                case 0: return connect_nested(s, gl, gu, hole);
                case 1: return connect_partition(s, gl, gu, true);
                case 4: return connect_partition(s, gl, gu, false);
                case 2: return connect_union(s, gl, gu, hole);
                default: return connect_hull(s, gl, gu, hole);
            }
        };
        // nested, partition keeping every branch, union ring, partition with
        // interior branches detached, convex hull.
        const std::string order = "04213";
        int first_built = -1;
        Status first_error = ok_status();
        for (char c : order) {
            const int method = c - '0';
            if (!one_side && (method < 2 || method == 4)) continue;
            Status status = construct(method);
            if (status && count_self_intersections(positions, std::span<const uint32_t>(triangles).subspan(tri0)) == 0)
                return status;
            if (status && first_built < 0) first_built = method;
            if (!status && first_error) first_error = status;
            roll_back();
        }
        if (first_built < 0)
            return first_error.ok() ? input_error(where(path_, *first_lower.source) + ": branching failed")
                                    : first_error;
        return construct(first_built);
    }

    // Holes of `parent` (slice `ps`) that end towards slice `os` (no hole there
    // links to them) and lie partly outside `other` there: the hole opens into
    // a notch of `other`.
    std::vector<uint32_t> open_holes(size_t ps, uint32_t parent, size_t os, uint32_t other) const {
        std::vector<uint32_t> holes_here, holes_there;
        for (uint32_t k = 0; k < loops_[ps].size(); ++k)
            if (loops_[ps][k].hole()) holes_here.push_back(k);
        for (uint32_t k = 0; k < loops_[os].size(); ++k)
            if (loops_[os][k].hole()) holes_there.push_back(k);
        std::vector<bool> linked(holes_here.size(), false);
        if (!holes_there.empty() && !holes_here.empty()) {
            std::vector<PolygonSpan> here, there;
            for (uint32_t k : holes_here) here.emplace_back(loops_[ps][k].xy);
            for (uint32_t k : holes_there) there.emplace_back(loops_[os][k].xy);
            const bool up = os > ps;
            for (const ContourLink& l :
                 correspond_contours(up ? std::span<const PolygonSpan>(here) : there,
                                     up ? std::span<const PolygonSpan>(there) : here, options_.correspondence))
                linked[up ? l.lower : l.upper] = true;
        }
        std::vector<uint32_t> open;
        for (size_t h = 0; h < holes_here.size(); ++h) {
            const Loop& loop = loops_[ps][holes_here[h]];
            if (linked[h] || loop.parent != int(parent)) continue;
            size_t outside = 0;
            for (const Vec2& p : loop.xy) outside += !point_in_polygon(p, loops_[os][other].xy);
            if (4 * outside >= loop.xy.size()) open.push_back(holes_here[h]);
        }
        return open;
    }

    // A 1:1 pair where a hole on one slice opens into a notch of the other
    // slice's contour: the contour without holes is split between the solid
    // contour and its open holes (nearest-branch partition, chords at mid-slice),
    // so the notch's walls run down to the hole instead of a band sweeping
    // across the solid. Returns false (nothing built) when no hole opens or the
    // construction would cross itself.
    Result<bool> connect_open_holes(size_t s, uint32_t lower, uint32_t upper) {
        for (int side = 0; side < 2; ++side) {
            const size_t ps = side == 0 ? s : s + 1, os = side == 0 ? s + 1 : s;
            const uint32_t parent = side == 0 ? lower : upper, other = side == 0 ? upper : lower;
            std::vector<uint32_t> branches = open_holes(ps, parent, os, other);
            if (branches.empty()) continue;
            branches.insert(branches.begin(), parent);
            // Chords at mid-slice, else as close to mid-slice as they can be
            // towards the notched contour without crossing (the hole's band then
            // has room to climb before it meets the chords; the bunny at 40
            // planes: 0.85 of the way, Hausdorff 0.0323 at 0.9, 0.0304 at 0.85).
            for (const double w : {0.5, 0.7, 0.85, 0.95}) {
                const size_t tri0 = triangles.size(), pos0 = positions.size();
                auto status = split(loops_[os][other].ids, loops_[ps], branches, w * z(os) + (1 - w) * z(ps), side == 1,
                                    loops_[ps][parent]);
                if (status &&
                    count_self_intersections(positions, std::span<const uint32_t>(triangles).subspan(tri0)) == 0) {
                    for (size_t b = 1; b < branches.size(); ++b)
                        (side == 0 ? loops_[ps][branches[b]].linked_up : loops_[ps][branches[b]].linked_down) = true;
                    return true;
                }
                triangles.resize(tri0);
                positions.resize(pos0);
            }
        }
        return false;
    }

    Status connect_nested(size_t s, const std::vector<uint32_t>& gl, const std::vector<uint32_t>& gu, bool hole) {
        if (gl.size() == 1 && nested(s, gl[0], s + 1, gu)) return nested_branch(s, gl[0], s + 1, gu, hole);
        if (gu.size() == 1 && nested(s + 1, gu[0], s, gl)) return nested_branch(s + 1, gu[0], s, gl, hole);
        return input_error("not nested");
    }

    Status connect_partition(size_t s, const std::vector<uint32_t>& gl, const std::vector<uint32_t>& gu, bool detach) {
        const Loop& first_lower = loops_[s][gl[0]];
        const double zl = z(s), zu = z(s + 1);
        if (gl.size() == 1) {
            const std::vector<uint32_t> kept = detach ? detach_interior(s, gl[0], s + 1, gu) : gu;
            if (kept.size() == 1) return band(first_lower.ids, loops_[s + 1][kept[0]].ids, first_lower);
            return split(first_lower.ids, loops_[s + 1], kept, 0.5 * (zl + zu), true, first_lower);
        }
        const std::vector<uint32_t> kept = detach ? detach_interior(s + 1, gu[0], s, gl) : gl;
        if (kept.size() == 1) return band(loops_[s][kept[0]].ids, loops_[s + 1][gu[0]].ids, first_lower);
        return split(loops_[s + 1][gu[0]].ids, loops_[s], kept, 0.5 * (zl + zu), false, first_lower);
    }

    // A mid-slice ring around the union of the group's regions (grown by a
    // small fraction of their size) takes N:1 below and 1:M above, each as a
    // nested region: the branch geometry stays inside the slab and within a
    // few grid cells of the union of the two slices' regions.
    Status connect_union(size_t s, const std::vector<uint32_t>& gl, const std::vector<uint32_t>& gu, bool hole) {
        const Loop& first_lower = loops_[s][gl[0]];
        const double zl = z(s), zu = z(s + 1), zm = 0.5 * (zl + zu);
        std::vector<std::span<const Vec2>> all;
        double perimeter = 0;
        size_t points = 0;
        for (uint32_t k : gl) all.emplace_back(loops_[s][k].xy);
        for (uint32_t k : gu) all.emplace_back(loops_[s + 1][k].xy);
        Aabb box;
        for (const auto& l : all)
            for (size_t i = 0; i < l.size(); ++i) {
                perimeter += glm::length(l[(i + 1) % l.size()] - l[i]);
                box.extend(Vec3(l[i], 0.0));
            }
        for (const auto& l : all) points += l.size();
        const double cell = std::clamp(0.5 * perimeter / double(points), box.extent() / 4000, box.extent() / 100);
        std::vector<Vec2> ring = union_ring(all, cell);
        if (ring.size() < 3) return input_error("no union ring");
        if (hole) std::reverse(ring.begin(), ring.end());
        for (const auto& l : all)
            for (const Vec2& p : l)
                if (!point_in_polygon(p, ring)) return input_error("union ring misses a contour");
        const std::vector<uint32_t> mid = lifted_copy(ring, zm);
        std::vector<const Loop*> below, above;
        for (uint32_t k : gl) below.push_back(&loops_[s][k]);
        for (uint32_t k : gu) above.push_back(&loops_[s + 1][k]);
        // Short walls at the ring (a tenth of the half spacing): the ring is the
        // widest outline of the pair, and the sheets reach the contours sooner.
        auto status = nested_region(ring, mid, zm, below, zl, hole, first_lower, 0.1);
        if (!status) return status;
        return nested_region(ring, mid, zm, above, zu, hole, first_lower, 0.1);
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
                         const std::vector<const Loop*>& inner, double z_inner, bool hole, const Loop& blame,
                         double wall_outer = 1.0 / 3, double wall_inner = 1.0 / 3) {
        const double z_a = z_outer + (z_inner - z_outer) * wall_outer, z_b = z_inner - (z_inner - z_outer) * wall_inner;
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
                        // A hole's void goes on past the slice where its band ends: its
                        // dome bulges away from the faces, into the solid (a dome towards
                        // the faces would stretch across the void the hole's band bounds).
                        const double height = loops[k].hole() && !slab ? -dome : dome;
                        auto status = build_cap(region, ids, at, face_up, style, height, positions, triangles);
                        if (!status) return input_error(where(path_, *loops[k].source) + ": " + status.error().message);
                    }
                }
            }
        }
        return ok_status();
    }
};

// One structure of a validated stack: its mesh and statistics.
Result<StructureMesh> build_structure(const ContourStack& stack, const Grouping& grouping, size_t i,
                                      const BuildOptions& options, const std::string& source_path,
                                      const std::function<void()>& advance) {
    const auto& members = grouping.members[i];
    size_t contours = 0;
    for (const auto& v : members) contours += v.size();
    const auto start = std::chrono::steady_clock::now();
    StructureBuilder builder(stack, options, source_path);
    auto status = builder.build(members, advance);
    if (!status) return status.error();
    StructureMesh sm;
    sm.id = grouping.infos[i].id;
    sm.contours = contours;
    sm.mesh.name = grouping.infos[i].name;
    sm.mesh.color = grouping.infos[i].color;
    sm.mesh.positions = std::move(builder.positions);
    sm.mesh.indices = std::move(builder.triangles);
    sm.fairing_restored = taubin_smooth(sm.mesh.positions, sm.mesh.indices, options.fairing);
    const MeshTopology topo = analyze_topology(sm.mesh.positions, sm.mesh.indices);
    sm.triangles = sm.mesh.triangle_count();
    sm.volume = mesh_volume(sm.mesh.positions, sm.mesh.indices);
    sm.area = mesh_area(sm.mesh.positions, sm.mesh.indices);
    sm.closed_manifold = topo.closed_manifold();
    sm.genus = topo.genus();
    sm.components = topo.components;
    sm.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return sm;
}

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

    // Stage 3: one mesh per structure, options.jobs at a time (structures are
    // independent). Results keep the structure order; the first error in that
    // order is the one reported, as in a one-thread build.
    std::vector<size_t> todo;
    for (size_t i = 0; i < grouping.infos.size(); ++i) {
        const auto& m = grouping.members[i];
        if (std::any_of(m.begin(), m.end(), [](const auto& v) { return !v.empty(); })) todo.push_back(i);
    }
    const size_t total = todo.size() * stack.slices.size();
    size_t done = 0;
    std::mutex progress_mutex;
    const std::function<void()> advance = [&] {
        if (!options.progress) return;
        std::lock_guard<std::mutex> lock(progress_mutex);
        options.progress(++done, total);
    };
    std::vector<std::optional<Result<StructureMesh>>> results(todo.size());
    std::atomic<size_t> next{0};
    std::atomic<bool> failed{false};
    auto worker = [&] {
        // Indices are taken in increasing order, so after a failure every
        // structure before it has been taken and finishes: nothing later is needed.
        for (size_t k = next++; k < todo.size() && !failed; k = next++) {
            results[k] = build_structure(stack, grouping, todo[k], options, source_path, advance);
            if (!results[k]->ok()) failed = true;
        }
    };
    const size_t threads = std::min<size_t>(std::max(options.jobs, 1u), todo.size());
    if (threads <= 1) {
        worker();
    } else {
        std::vector<std::thread> pool;
        for (size_t t = 0; t < threads; ++t) pool.emplace_back(worker);
        for (auto& t : pool) t.join();
    }
    std::vector<StructureMesh> out;
    for (auto& r : results) {
        if (!r) break;  // not taken: only after a failure, which comes first in this order
        if (!r->ok()) return r->error();
        out.push_back(std::move(r->value()));
    }
    return out;
}

}  // namespace body
