// Quadric-error simplification recorded as vertex splits.
//
// References:
//   M. Garland, P. Heckbert, "Surface Simplification Using Quadric Error Metrics", SIGGRAPH 1997.
//   H. Hoppe, "Progressive Meshes", SIGGRAPH 1996.
//   T. Dey, H. Edelsbrunner, S. Guha, D. Nekhayev, "Topology preserving edge contraction", 1999
//     (the link condition).
//
// Pipeline (static phases, public entry at the bottom):
//   clean_input      drop degenerate triangles and unreferenced vertices
//   build_adjacency  per-vertex corner lists (singly linked through corners), boundary/non-manifold flags
//   init_quadrics    area-weighted plane quadrics + boundary penalty planes (ordering) and unit-weight
//                    quadrics (the stored object-space error)
//   collapse_loop    binary heap of directed half-edge collapses with lazy invalidation
//   emit_order       vertices and faces in refinement order, index patches per split
#include "builder/lod/simplify.h"

#include <algorithm>
#include <cmath>

#include "shared/pm/bpm_format.h"

namespace body::lod {
namespace {

constexpr uint32_t kNone = 0xffffffffu;
constexpr double kMinTurnCos = 0.2;  // cos(78 degrees): the largest turn of a face in one collapse
constexpr double kFoldCos = -0.9;    // neighbours closer than 26 degrees to back-to-back count as folded

// Symmetric 4x4 quadric: A (6), b (3), c.
struct Quadric {
    double a00 = 0, a01 = 0, a02 = 0, a11 = 0, a12 = 0, a22 = 0, b0 = 0, b1 = 0, b2 = 0, c = 0;

    static Quadric plane(const Vec3& n, double d, double w) {
        Quadric q;
        q.a00 = w * n.x * n.x;
        q.a01 = w * n.x * n.y;
        q.a02 = w * n.x * n.z;
        q.a11 = w * n.y * n.y;
        q.a12 = w * n.y * n.z;
        q.a22 = w * n.z * n.z;
        q.b0 = w * n.x * d;
        q.b1 = w * n.y * d;
        q.b2 = w * n.z * d;
        q.c = w * d * d;
        return q;
    }
    void add(const Quadric& o) {
        a00 += o.a00;
        a01 += o.a01;
        a02 += o.a02;
        a11 += o.a11;
        a12 += o.a12;
        a22 += o.a22;
        b0 += o.b0;
        b1 += o.b1;
        b2 += o.b2;
        c += o.c;
    }
    double eval(const Vec3& p) const {
        const double x = p.x, y = p.y, z = p.z;
        const double ax = a00 * x + a01 * y + a02 * z;
        const double ay = a01 * x + a11 * y + a12 * z;
        const double az = a02 * x + a12 * y + a22 * z;
        return x * ax + y * ay + z * az + 2.0 * (b0 * x + b1 * y + b2 * z) + c;
    }
    double eval_sum(const Quadric& o, const Vec3& p) const {
        Quadric s = *this;
        s.add(o);
        return s.eval(p);
    }
};

struct HeapEntry {
    double cost;
    uint32_t from, to;
    uint32_t stamp_from, stamp_to;
};
// Min-heap order with a total tie-break so the sequence never depends on the platform.
struct HeapAfter {
    bool operator()(const HeapEntry& a, const HeapEntry& b) const {
        if (a.cost != b.cost) return a.cost > b.cost;
        if (a.from != b.from) return a.from > b.from;
        return a.to > b.to;
    }
};

struct Collapse {
    uint32_t from, to;
    uint32_t removed[2];
    uint32_t removed_count;
    uint32_t patch_begin, patch_end;
    double error;
};

struct State {
    std::vector<Vec3> pos;
    std::vector<uint32_t> idx;           // 3 per face, current
    std::vector<uint8_t> face_alive;     // per face
    std::vector<uint8_t> edge_boundary;  // per corner: edge corner -> next corner has one face
    std::vector<uint32_t> head, next;    // corner lists
    std::vector<uint32_t> fcount;        // live faces per vertex
    std::vector<uint8_t> boundary, locked, alive;
    std::vector<uint32_t> stamp;
    std::vector<Quadric> q, e;  // ordering quadric, error quadric
    std::vector<HeapEntry> heap;
    std::vector<Collapse> collapses;
    std::vector<uint32_t> patch_faces;
    size_t live_faces = 0;
    double running_error = 0.0;
    // scratch
    std::vector<uint32_t> cu, ring_u, ring_v;
};

// ---------------------------------------------------------------- phases

// Compacts the input: keeps non-degenerate triangles and the vertices they use,
// in input order (kept_vertex[i] = input index of vertex i).
void clean_input(const Mesh& mesh, State& s, std::vector<uint32_t>& kept_vertex) {
    const size_t n = mesh.positions.size();
    std::vector<uint32_t> remap(n, kNone);
    for (size_t f = 0; f + 2 < mesh.indices.size(); f += 3) {
        const uint32_t a = mesh.indices[f], b = mesh.indices[f + 1], c = mesh.indices[f + 2];
        if (a >= n || b >= n || c >= n || a == b || b == c || a == c) continue;
        remap[a] = remap[b] = remap[c] = 0;
        s.idx.insert(s.idx.end(), {a, b, c});
    }
    for (size_t v = 0; v < n; ++v) {
        if (remap[v] == kNone) continue;
        remap[v] = uint32_t(kept_vertex.size());
        kept_vertex.push_back(uint32_t(v));
        s.pos.push_back(mesh.positions[v]);
    }
    for (uint32_t& v : s.idx) v = remap[v];
}

void build_adjacency(State& s) {
    const size_t n = s.pos.size(), corners = s.idx.size(), faces = corners / 3;
    s.head.assign(n, kNone);
    s.next.assign(corners, kNone);
    s.fcount.assign(n, 0);
    for (size_t c = corners; c-- > 0;) {
        uint32_t v = s.idx[c];
        s.next[c] = s.head[v];
        s.head[v] = uint32_t(c);
        ++s.fcount[v];
    }
    s.face_alive.assign(faces, 1);
    s.live_faces = faces;
    // Edge multiplicity through sorted undirected keys (deterministic, no hashing).
    std::vector<std::pair<uint64_t, uint32_t>> keys(corners);
    for (size_t c = 0; c < corners; ++c) {
        uint32_t a = s.idx[c], b = s.idx[c - c % 3 + (c + 1) % 3];
        keys[c] = {uint64_t(std::min(a, b)) << 32 | std::max(a, b), uint32_t(c)};
    }
    std::sort(keys.begin(), keys.end());
    s.edge_boundary.assign(corners, 0);
    s.boundary.assign(n, 0);
    s.locked.assign(n, 0);
    for (size_t i = 0; i < keys.size();) {
        size_t j = i;
        while (j < keys.size() && keys[j].first == keys[i].first) ++j;
        const uint32_t a = uint32_t(keys[i].first >> 32), b = uint32_t(keys[i].first);
        if (j - i == 1) {
            s.edge_boundary[keys[i].second] = 1;
            s.boundary[a] = s.boundary[b] = 1;
        } else if (j - i > 2) {
            s.locked[a] = s.locked[b] = 1;  // non-manifold edge: never move its ends
        } else {
            // Two faces must traverse the edge in opposite directions.
            uint32_t c0 = keys[i].second, c1 = keys[i + 1].second;
            if (s.idx[c0] == s.idx[c1]) s.locked[a] = s.locked[b] = 1;
        }
        i = j;
    }
    s.alive.assign(n, 1);
    s.stamp.assign(n, 0);
}

void init_quadrics(State& s, double boundary_weight) {
    const size_t n = s.pos.size(), faces = s.idx.size() / 3;
    s.q.assign(n, Quadric{});
    s.e.assign(n, Quadric{});
    for (size_t f = 0; f < faces; ++f) {
        const uint32_t* t = &s.idx[f * 3];
        const Vec3 &p0 = s.pos[t[0]], &p1 = s.pos[t[1]], &p2 = s.pos[t[2]];
        Vec3 nrm = glm::cross(p1 - p0, p2 - p0);
        const double len = glm::length(nrm);
        if (!(len > 0.0)) continue;
        nrm /= len;
        const double d = -glm::dot(nrm, p0);
        const Quadric area = Quadric::plane(nrm, d, 0.5 * len), unit = Quadric::plane(nrm, d, 1.0);
        for (int k = 0; k < 3; ++k) {
            s.q[t[k]].add(area);
            s.e[t[k]].add(unit);
        }
        for (int k = 0; k < 3; ++k) {
            if (!s.edge_boundary[f * 3 + k]) continue;
            const Vec3 &a = s.pos[t[k]], &b = s.pos[t[(k + 1) % 3]];
            const Vec3 edge = b - a;
            Vec3 bn = glm::cross(edge, nrm);
            const double bl = glm::length(bn);
            if (!(bl > 0.0)) continue;
            bn /= bl;
            const double bd = -glm::dot(bn, a);
            const Quadric pen = Quadric::plane(bn, bd, boundary_weight * glm::dot(edge, edge));
            const Quadric upen = Quadric::plane(bn, bd, 1.0);
            for (uint32_t v : {t[k], t[(k + 1) % 3]}) {
                s.q[v].add(pen);
                s.e[v].add(upen);
            }
        }
    }
}

// Live corners of v, compacting dead ones out of its list on the way.
void live_corners(State& s, uint32_t v, std::vector<uint32_t>& out) {
    out.clear();
    uint32_t* link = &s.head[v];
    while (*link != kNone) {
        const uint32_t c = *link;
        if (!s.face_alive[c / 3]) {
            *link = s.next[c];
            continue;
        }
        out.push_back(c);
        link = &s.next[c];
    }
}

void ring_of(State& s, uint32_t v, std::vector<uint32_t>& ring) {
    ring.clear();
    for (uint32_t c = s.head[v]; c != kNone; c = s.next[c]) {
        if (!s.face_alive[c / 3]) continue;
        const uint32_t f = c / 3 * 3;
        for (int k = 0; k < 3; ++k)
            if (s.idx[f + k] != v) ring.push_back(s.idx[f + k]);
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
}

void push_candidate(State& s, uint32_t from, uint32_t to) {
    if (s.locked[from] || !s.alive[from] || !s.alive[to]) return;
    const double cost = s.q[from].eval_sum(s.q[to], s.pos[to]);
    s.heap.push_back({std::max(cost, 0.0), from, to, s.stamp[from], s.stamp[to]});
    std::push_heap(s.heap.begin(), s.heap.end(), HeapAfter{});
}

void push_all_candidates(State& s) {
    s.heap.clear();
    for (size_t c = 0; c < s.idx.size(); ++c) {
        if (!s.face_alive[c / 3]) continue;
        const uint32_t a = s.idx[c], b = s.idx[c - c % 3 + (c + 1) % 3];
        push_candidate(s, a, b);
        if (s.edge_boundary[c]) push_candidate(s, b, a);
    }
}

bool third_vertex(const State& s, uint32_t face, uint32_t u, uint32_t v, uint32_t& out) {
    const uint32_t* t = &s.idx[face * 3];
    bool has_v = false;
    for (int k = 0; k < 3; ++k) {
        if (t[k] == v)
            has_v = true;
        else if (t[k] != u)
            out = t[k];
    }
    return has_v;
}

// Unit normal of face f with vertex u placed at p.
Vec3 face_normal(const State& s, uint32_t f, uint32_t u, const Vec3& p) {
    const uint32_t* t = &s.idx[f * 3];
    Vec3 r[3];
    for (int k = 0; k < 3; ++k) r[k] = t[k] == u ? p : s.pos[t[k]];
    const Vec3 n = glm::cross(r[1] - r[0], r[2] - r[0]);
    const double l = glm::length(n);
    return l > 0.0 ? n / l : Vec3(0.0);
}

// The live face traversing edge b -> a (the neighbour of a face with edge a -> b).
uint32_t face_across(const State& s, uint32_t a, uint32_t b) {
    for (uint32_t c = s.head[b]; c != kNone; c = s.next[c]) {
        const uint32_t f = c / 3;
        if (!s.face_alive[f]) continue;
        if (s.idx[f * 3 + (c % 3 + 1) % 3] == a) return f;
    }
    return kNone;
}

// Checks topology and geometry of the half-edge collapse u -> v (u disappears).
// Fills s.cu with u's live corners; `shared` gets the faces removed.
bool collapse_allowed(State& s, uint32_t u, uint32_t v, uint32_t shared[2], uint32_t& shared_count) {
    live_corners(s, u, s.cu);
    shared_count = 0;
    uint32_t opposite[2] = {kNone, kNone};
    for (uint32_t c : s.cu) {
        uint32_t a = kNone;
        if (third_vertex(s, c / 3, u, v, a)) {
            if (shared_count == 2) return false;  // non-manifold edge
            opposite[shared_count] = a;
            shared[shared_count++] = c / 3;
        }
    }
    if (shared_count == 0) return false;  // no longer an edge
    // A boundary vertex may only slide along its boundary edge; an interior one over an interior edge.
    if (s.boundary[u] ? shared_count != 1 : shared_count != 2) return false;
    // Link condition: the common neighbours of u and v are exactly the opposite vertices.
    ring_of(s, u, s.ring_u);
    ring_of(s, v, s.ring_v);
    size_t common = 0;
    for (size_t i = 0, j = 0; i < s.ring_u.size() && j < s.ring_v.size();) {
        if (s.ring_u[i] < s.ring_v[j])
            ++i;
        else if (s.ring_v[j] < s.ring_u[i])
            ++j;
        else {
            ++common;
            ++i;
            ++j;
        }
    }
    if (common != shared_count) return false;
    // Opposite vertices lose a face; keep their fans valid (no structure collapses to nothing).
    for (uint32_t i = 0; i < shared_count; ++i) {
        const uint32_t a = opposite[i];
        if (s.fcount[a] <= (s.boundary[a] ? 1u : 3u)) return false;
    }
    const uint32_t merged = s.fcount[u] + s.fcount[v] - 2 * shared_count;
    if (merged > pm::kMaxPatchFan || merged < (s.boundary[v] ? 1u : 3u)) return false;
    // Geometry: no face of u may flip or become a sliver when u moves onto v.
    const Vec3& target = s.pos[v];
    for (uint32_t c : s.cu) {
        const uint32_t f = c / 3;
        if (f == shared[0] || (shared_count == 2 && f == shared[1])) continue;
        const uint32_t* t = &s.idx[f * 3];
        Vec3 p[3], r[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = s.pos[t[k]];
            r[k] = t[k] == u ? target : p[k];
        }
        const Vec3 n0 = glm::cross(p[1] - p[0], p[2] - p[0]);
        const Vec3 n1 = glm::cross(r[1] - r[0], r[2] - r[0]);
        // Flip and fold guard: a face may turn by at most kMaxTurn per collapse.
        if (!(glm::dot(n0, n1) > kMinTurnCos * std::sqrt(glm::dot(n0, n0) * glm::dot(n1, n1)))) return false;
        const double l2 = std::max({glm::dot(r[1] - r[0], r[1] - r[0]), glm::dot(r[2] - r[1], r[2] - r[1]),
                                    glm::dot(r[0] - r[2], r[0] - r[2])});
        if (glm::dot(n1, n1) <= 1e-12 * l2 * l2) return false;
    }
    // Fold guard: a moved face must not end up (nearly) back to back with a neighbour
    // unless it already was.
    for (uint32_t c : s.cu) {
        const uint32_t f = c / 3;
        if (f == shared[0] || (shared_count == 2 && f == shared[1])) continue;
        const uint32_t* t = &s.idx[f * 3];
        const Vec3 n_old = face_normal(s, f, u, s.pos[u]), n_new = face_normal(s, f, u, target);
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = t[k], b = t[(k + 1) % 3];
            const uint32_t g = face_across(s, a, b);
            if (g == kNone || g == shared[0] || (shared_count == 2 && g == shared[1])) continue;
            const double before = glm::dot(n_old, face_normal(s, g, u, s.pos[u]));
            const double after = glm::dot(n_new, face_normal(s, g, u, target));
            if (after < kFoldCos && after < before) return false;
        }
    }
    return true;
}

void apply_collapse(State& s, uint32_t u, uint32_t v, const uint32_t shared[2], uint32_t shared_count) {
    Collapse rec{};
    rec.from = u;
    rec.to = v;
    rec.removed_count = shared_count;
    rec.removed[0] = shared[0];
    rec.removed[1] = shared_count == 2 ? shared[1] : kNone;
    rec.patch_begin = uint32_t(s.patch_faces.size());
    const double err = std::sqrt(std::max(0.0, s.e[u].eval_sum(s.e[v], s.pos[v])));
    s.running_error = std::max(s.running_error, err);
    rec.error = s.running_error;
    for (uint32_t i = 0; i < shared_count; ++i) {
        const uint32_t f = shared[i];
        s.face_alive[f] = 0;
        for (int k = 0; k < 3; ++k) --s.fcount[s.idx[f * 3 + k]];
        --s.live_faces;
    }
    // Move u's surviving corners onto v (s.cu holds u's live corners from the check).
    for (uint32_t c : s.cu) {
        if (!s.face_alive[c / 3]) continue;
        s.idx[c] = v;
        s.patch_faces.push_back(c / 3);
        s.next[c] = s.head[v];
        s.head[v] = c;
        ++s.fcount[v];
    }
    s.head[u] = kNone;
    s.fcount[u] = 0;
    s.alive[u] = 0;
    rec.patch_end = uint32_t(s.patch_faces.size());
    s.collapses.push_back(rec);
    s.q[v].add(s.q[u]);
    s.e[v].add(s.e[u]);
    ++s.stamp[v];
    // Every collapse touching v changed cost; re-queue both directions of each edge of v.
    ring_of(s, v, s.ring_v);
    for (uint32_t x : s.ring_v) {
        push_candidate(s, x, v);
        push_candidate(s, v, x);
    }
}

void collapse_loop(State& s, size_t target_faces) {
    push_all_candidates(s);
    for (int pass = 0; pass < 16; ++pass) {
        size_t done = 0;
        while (!s.heap.empty() && s.live_faces > target_faces) {
            std::pop_heap(s.heap.begin(), s.heap.end(), HeapAfter{});
            const HeapEntry e = s.heap.back();
            s.heap.pop_back();
            if (!s.alive[e.from] || !s.alive[e.to] || s.stamp[e.from] != e.stamp_from || s.stamp[e.to] != e.stamp_to)
                continue;
            uint32_t shared[2], shared_count = 0;
            if (!collapse_allowed(s, e.from, e.to, shared, shared_count)) continue;
            apply_collapse(s, e.from, e.to, shared, shared_count);
            ++done;
        }
        // Collapses rejected earlier may have become legal as their neighbourhoods changed.
        if (done == 0 || s.live_faces <= target_faces) break;
        push_all_candidates(s);
    }
}

ProgressiveBuild emit_order(const State& s, const std::vector<Vec3>& normals) {
    ProgressiveBuild pm;
    const size_t n = s.pos.size(), faces = s.idx.size() / 3, splits = s.collapses.size();
    std::vector<uint32_t> vid(n, kNone), fid(faces, kNone);
    uint32_t next_v = 0, next_f = 0;
    for (size_t v = 0; v < n; ++v)
        if (s.alive[v]) vid[v] = next_v++;
    pm.base_vertices = next_v;
    for (size_t f = 0; f < faces; ++f)
        if (s.face_alive[f]) fid[f] = next_f++;
    pm.base_faces = next_f;
    for (size_t j = 0; j < splits; ++j) {
        const Collapse& c = s.collapses[splits - 1 - j];
        vid[c.from] = next_v++;
        for (uint32_t i = 0; i < c.removed_count; ++i) fid[c.removed[i]] = next_f++;
    }
    pm.positions.resize(next_v);
    pm.normals.resize(next_v);
    for (size_t v = 0; v < n; ++v) {
        if (vid[v] == kNone) continue;
        pm.positions[vid[v]] = s.pos[v];
        pm.normals[vid[v]] = normals[v];
    }
    pm.indices.resize(size_t(next_f) * 3);
    for (size_t f = 0; f < faces; ++f) {
        if (fid[f] == kNone) continue;
        for (int k = 0; k < 3; ++k) pm.indices[fid[f] * 3 + k] = vid[s.idx[f * 3 + k]];
    }
    pm.splits.resize(splits);
    pm.patch_begin.assign(splits + 1, 0);
    for (size_t j = 0; j < splits; ++j) {
        const Collapse& c = s.collapses[splits - 1 - j];
        pm.splits[j] = {vid[c.to], c.removed_count, c.error};
        for (uint32_t i = c.patch_begin; i < c.patch_end; ++i) pm.patch_faces.push_back(fid[s.patch_faces[i]]);
        pm.patch_begin[j + 1] = uint32_t(pm.patch_faces.size());
    }
    return pm;
}

}  // namespace

Result<ProgressiveBuild> build_progressive_mesh(const Mesh& mesh, const LodOptions& options) {
    State s;
    std::vector<uint32_t> kept;
    clean_input(mesh, s, kept);
    if (s.idx.empty()) return input_error("lod: mesh '" + mesh.name + "' has no non-degenerate triangles");
    if (s.pos.size() >= (1u << 28)) return input_error("lod: mesh '" + mesh.name + "' is too large");
    std::vector<Vec3> normals(s.pos.size());
    if (mesh.normals.size() == mesh.positions.size()) {
        for (size_t i = 0; i < kept.size(); ++i) {
            const double l = glm::length(mesh.normals[kept[i]]);
            normals[i] = l > 0.0 ? mesh.normals[kept[i]] / l : Vec3(0, 0, 1);
        }
    } else {
        normals = vertex_normals(s.pos, s.idx);
    }
    build_adjacency(s);
    init_quadrics(s, options.boundary_weight);
    collapse_loop(s, std::max<size_t>(options.min_triangles, 1));
    return emit_order(s, normals);
}

Mesh extract_level(const ProgressiveBuild& pm, size_t level) {
    level = std::min(level, pm.splits.size());
    size_t faces = pm.base_faces;
    for (size_t j = 0; j < level; ++j) faces += pm.splits[j].face_count;
    Mesh m;
    m.positions.assign(pm.positions.begin(), pm.positions.begin() + ptrdiff_t(pm.base_vertices + level));
    m.indices.assign(pm.indices.begin(), pm.indices.begin() + ptrdiff_t(faces * 3));
    // Faces are stored as they are when they appear; replay the index patches.
    for (size_t j = 0; j < level; ++j) {
        const uint32_t child = uint32_t(pm.base_vertices + j), parent = pm.splits[j].parent;
        for (uint32_t i = pm.patch_begin[j]; i < pm.patch_begin[j + 1]; ++i) {
            uint32_t* t = &m.indices[size_t(pm.patch_faces[i]) * 3];
            for (int k = 0; k < 3; ++k)
                if (t[k] == parent) t[k] = child;
        }
    }
    return m;
}

}  // namespace body::lod
