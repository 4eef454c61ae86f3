// The simplifier's setup (simplify_state.h): the input compacted, the adjacency,
// vertices and faces renumbered for cache locality, and the quadrics.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "builder/lod/simplify_state.h"

namespace body::lod::detail {

// Compacts the input: keeps non-degenerate triangles and the vertices they use,
// in input order (kept_vertex[i] = input index of vertex i).
void clean_input(const Mesh& mesh, Surface& s, PrefaultedVector<uint32_t>& kept_vertex) {
    const size_t n = mesh.positions.size();
    PrefaultedVector<uint32_t> remap(n, kNone);
    s.idx.reserve(mesh.indices.size());
    for (size_t f = 0; f + 2 < mesh.indices.size(); f += 3) {
        const uint32_t a = mesh.indices[f], b = mesh.indices[f + 1], c = mesh.indices[f + 2];
        if (a >= n || b >= n || c >= n || a == b || b == c || a == c) continue;
        remap[a] = remap[b] = remap[c] = 0;
        s.idx.insert(s.idx.end(), {a, b, c});
    }
    kept_vertex.reserve(n);
    s.pos.reserve(n);
    for (size_t v = 0; v < n; ++v) {
        if (remap[v] == kNone) continue;
        remap[v] = uint32_t(kept_vertex.size());
        kept_vertex.push_back(uint32_t(v));
        s.pos.push_back(mesh.positions[v]);
    }
    for (uint32_t& v : s.idx) v = remap[v];
}

void build_adjacency(Surface& s) {
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
    // Edge multiplicity from the fans: the faces around a that also contain b are
    // the faces of edge {a, b} (no sort over all corners; the same flags). Each fan
    // is walked once into a local list that all its corners then scan.
    s.edge_boundary.assign(corners, 0);
    s.across.assign(corners, kUnknown);
    s.boundary.assign(n, 0);
    s.locked.assign(n, 0);
    struct FanCorner {
        uint32_t after, before, face, corner;
    };
    std::vector<FanCorner> fan;
    for (uint32_t a = 0; a < n; ++a) {
        fan.clear();
        for (uint32_t d = s.head[a]; d != kNone; d = s.next[d]) {
            const uint32_t f = d - d % 3;
            fan.push_back({s.idx[f + (d % 3 + 1) % 3], s.idx[f + (d % 3 + 2) % 3], f, d});
        }
        for (const FanCorner& c : fan) {  // edge a -> c.after
            const uint32_t b = c.after;
            uint32_t count = 0;
            bool same_direction = false;  // another face also runs a -> b
            uint32_t other = kNone;       // the face running b -> a
            for (const FanCorner& d : fan) {
                if (d.after != b && d.before != b) continue;
                ++count;
                if (d.after == b && d.face != c.face) same_direction = true;
                if (d.before == b) other = d.face / 3;
            }
            if (count == 2 && !same_direction) s.across[c.corner] = other;
            if (count == 1) {
                s.across[c.corner] = kNone;
                s.edge_boundary[c.corner] = 1;
                s.boundary[a] = s.boundary[b] = 1;
            } else if (count > 2 || same_direction) {
                s.locked[a] = s.locked[b] = kLocked;  // non-manifold edge: never move its ends
            }
        }
    }
    s.alive.assign(n, 1);
}

// The plane of face f: unit normal, offset and twice the area (false: degenerate).
template <class S>
static bool face_plane(const S& s, size_t f, Vec3& nrm, double& d, double& len) {
    const uint32_t* t = &s.idx[f * 3];
    const Vec3 &p0 = s.pos[t[0]], &p1 = s.pos[t[1]], &p2 = s.pos[t[2]];
    nrm = glm::cross(p1 - p0, p2 - p0);
    len = glm::length(nrm);
    if (!(len > 0.0)) return false;
    nrm /= len;
    d = -glm::dot(nrm, p0);
    return true;
}

// The boundary-preserving plane through edge k of face f (normal `nrm`), perpendicular to
// the face: unit weight in `unit`, boundary_weight x edge length^2 in `weighted`.
template <class S>
static bool boundary_planes(const S& s, size_t f, int k, const Vec3& nrm, double boundary_weight, Quadric& weighted,
                            Quadric& unit) {
    const uint32_t* t = &s.idx[f * 3];
    const Vec3 &a = s.pos[t[k]], &b = s.pos[t[(k + 1) % 3]];
    const Vec3 edge = b - a;
    Vec3 bn = glm::cross(edge, nrm);
    const double bl = glm::length(bn);
    if (!(bl > 0.0)) return false;
    bn /= bl;
    const double bd = -glm::dot(bn, a);
    weighted = Quadric::plane(bn, bd, boundary_weight * glm::dot(edge, edge));
    unit = Quadric::plane(bn, bd, 1.0);
    return true;
}

// The ordering and error quadrics of every vertex from the input faces. Gathered per
// vertex over its corner list (the input's face order, which reorder_faces keeps), face
// planes recomputed at each corner: each vertex's sums are written once, in Morton
// order, where adding each face to its three vertices' sums in face order cost a
// scattered read-modify-write of six quadrics per face (the input's face order is
// unrelated to the vertex order). The per-vertex
// summation order is the same (area plane, then the face's boundary edges at that vertex
// in edge order), so the sums are the same bit for bit.
void init_quadrics(Surface& s, double boundary_weight, uint32_t first, uint32_t end) {
    for (uint32_t v = first; v < end; ++v) {
        Quadric q, e;
        for (uint32_t c = s.head[v]; c != kNone; c = s.next[c]) {
            const uint32_t f = c / 3, at = c % 3;
            Vec3 nrm;
            double d = 0.0, len = 0.0;
            if (!face_plane(s, f, nrm, d, len)) continue;
            q.add(Quadric::plane(nrm, d, 0.5 * len));
            e.add(Quadric::plane(nrm, d, 1.0));
            // The face's edges at v (v -> next and previous -> v), in edge order.
            const int out = int(at), in = int(at + 2) % 3;
            for (const int k : {std::min(out, in), std::max(out, in)}) {
                Quadric pen, upen;
                if (!s.edge_boundary[f * 3 + k] || !boundary_planes(s, f, k, nrm, boundary_weight, pen, upen)) continue;
                q.add(pen);
                e.add(upen);
            }
        }
        s.q[v] = q;
        s.e[v] = e;
    }
}

// The ordering quadrics again, from the live faces (restart_ordering); face by face (the
// corner lists are no longer in face order).
void rebuild_ordering_quadrics(State& s, double boundary_weight) {
    const size_t faces = s.idx.size() / 3;
    std::fill(s.q.begin(), s.q.end(), Quadric{});
    for (size_t f = 0; f < faces; ++f) {
        if (!s.face_alive[f]) continue;
        Vec3 nrm;
        double d = 0.0, len = 0.0;
        if (!face_plane(s, f, nrm, d, len)) continue;
        const uint32_t* t = &s.idx[f * 3];
        const Quadric area = Quadric::plane(nrm, d, 0.5 * len);
        for (int k = 0; k < 3; ++k) s.q[t[k]].add(area);
        for (int k = 0; k < 3; ++k) {
            Quadric pen, upen;
            if (!s.edge_boundary[f * 3 + k] || !boundary_planes(s, f, k, nrm, boundary_weight, pen, upen)) continue;
            s.q[t[k]].add(pen);
            s.q[t[(k + 1) % 3]].add(pen);
        }
    }
}

// Renumbers the vertices along a Morton curve over the bounding box (10 bits per
// axis, ties by input number) so that a neighbourhood's vertices share cache lines;
// many inputs (subdivided meshes, merged OBJ objects) append vertices in an order
// unrelated to the surface. The flags and normals move with their vertex (the quadrics are built after).
void reorder_vertices(Surface& s, PrefaultedVector<Vec3>& normals) {
    const size_t n = s.pos.size();
    const Aabb box = mesh_bounds(s.pos);
    const Vec3 extent = box.max - box.min;
    auto cell = [](double t) {  // t in [0, 1] -> 0 .. 1023
        return uint64_t(std::clamp(t * 1024.0, 0.0, 1023.0));
    };
    auto spread = [](uint64_t x) {  // 10 bits -> every third bit of 30
        x = (x | (x << 16)) & 0x030000FFull;
        x = (x | (x << 8)) & 0x0300F00Full;
        x = (x | (x << 4)) & 0x030C30C3ull;
        x = (x | (x << 2)) & 0x09249249ull;
        return x;
    };
    PrefaultedVector<uint64_t> keys(n);
    for (size_t v = 0; v < n; ++v) {
        const Vec3 d = s.pos[v] - box.min;
        const uint64_t x = cell(extent.x > 0.0 ? d.x / extent.x : 0.0), y = cell(extent.y > 0.0 ? d.y / extent.y : 0.0),
                       z = cell(extent.z > 0.0 ? d.z / extent.z : 0.0);
        keys[v] = (spread(x) | spread(y) << 1 | spread(z) << 2) << 32 | v;
    }
    std::sort(keys.begin(), keys.end());
    s.rank.resize(n);
    s.vertex_of_input.resize(n);
    for (size_t i = 0; i < n; ++i) {
        s.rank[i] = uint32_t(keys[i]);
        s.vertex_of_input[s.rank[i]] = uint32_t(i);
    }
    auto permute = [&](auto& values) {
        std::remove_reference_t<decltype(values)> out(n);
        for (size_t i = 0; i < n; ++i) out[i] = values[s.rank[i]];
        values.swap(out);
    };
    permute(s.pos);
    permute(normals);
    permute(s.boundary);
    permute(s.locked);
    permute(s.alive);
    permute(s.fcount);
    for (uint32_t& v : s.idx) v = s.vertex_of_input[v];
}

// Renumbers the faces by their smallest vertex (stable), so that a fan's faces lie
// close together in every per-face and per-corner array: the input's face order
// may be unrelated to its vertex order (bunny: the next face's vertices lie ~700
// vertices away), and the collapse loop is bound by memory latency. Runs after the
// quadrics (their sums keep the input's order); the output does not depend on face
// numbers (emit_order restores the input order through face_of_input).
void reorder_faces(Surface& s) {
    const size_t n = s.pos.size(), faces = s.idx.size() / 3;
    PrefaultedVector<uint32_t> start(n + 1, 0);
    for (size_t f = 0; f < faces; ++f) ++start[std::min({s.idx[f * 3], s.idx[f * 3 + 1], s.idx[f * 3 + 2]}) + 1];
    for (size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    s.face_of_input.resize(faces);
    PrefaultedVector<uint32_t> idx(s.idx.size());
    PrefaultedVector<uint8_t> edge_boundary(s.idx.size());
    PrefaultedVector<uint32_t> across(s.idx.size());
    for (size_t f = 0; f < faces; ++f) {
        const uint32_t g = start[std::min({s.idx[f * 3], s.idx[f * 3 + 1], s.idx[f * 3 + 2]})]++;
        s.face_of_input[f] = g;
        for (int k = 0; k < 3; ++k) {
            idx[g * 3 + k] = s.idx[f * 3 + k];
            edge_boundary[g * 3 + k] = s.edge_boundary[f * 3 + k];
            across[g * 3 + k] = s.across[f * 3 + k];
        }
    }
    s.idx.swap(idx);
    s.edge_boundary.swap(edge_boundary);
    for (uint32_t& g : across)
        if (g < kUnknown) g = s.face_of_input[g];
    s.across.swap(across);
    // The corner lists in the input's order, as build_adjacency made them: the order
    // of a fan's walk decides which of a split's faces comes first in the output.
    s.head.assign(n, kNone);
    for (size_t f = faces; f-- > 0;)
        for (uint32_t k = 3; k-- > 0;) {
            const uint32_t c = s.face_of_input[f] * 3 + k;
            s.next[c] = s.head[s.idx[c]];
            s.head[s.idx[c]] = c;
        }
}

}  // namespace body::lod::detail
