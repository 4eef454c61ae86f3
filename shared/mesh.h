#pragma once
// Indexed triangle meshes and their topology checks.
//
// A Mesh owns its arrays: positions (one per vertex) and indices (three per
// triangle, counter-clockwise seen from outside). Units are those of the input
// (millimetres for anatomy). Normals are optional (empty or one per vertex).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "shared/geometry.h"

namespace body {

struct Mesh {
    std::string name;
    Vec3 color{0.8, 0.8, 0.8};
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices;
    std::vector<Vec3> normals;

    size_t vertex_count() const { return positions.size(); }
    size_t triangle_count() const { return indices.size() / 3; }
};

struct MeshTopology {
    size_t vertices = 0, triangles = 0, edges = 0;
    size_t boundary_edges = 0;        // edges used by one triangle
    size_t nonmanifold_edges = 0;     // edges used by three or more triangles
    size_t misoriented_edges = 0;     // edges whose two triangles traverse it the same way
    size_t nonmanifold_vertices = 0;  // vertices whose triangle fan is not one disc/cycle
    size_t degenerate_triangles = 0;  // repeated index or area below the tolerance
    size_t components = 0;            // connected components over shared edges
    long euler = 0;                   // V - E + F over referenced vertices
    // Closed, edge- and vertex-manifold, consistently oriented, no degenerate triangle.
    bool closed_manifold() const {
        return boundary_edges == 0 && nonmanifold_edges == 0 && misoriented_edges == 0 && nonmanifold_vertices == 0 &&
               degenerate_triangles == 0 && triangles > 0;
    }
    // Sum of genera over components; meaningful only for closed manifolds.
    long genus() const { return (2 * static_cast<long>(components) - euler) / 2; }
};

// Topology of a triangle soup given as indices into `positions`.
// `degenerate_area` is the area below which a triangle counts as degenerate.
MeshTopology analyze_topology(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                              double degenerate_area = 0.0);

// Signed volume enclosed (positive for outward orientation) and surface area.
double mesh_volume(std::span<const Vec3> positions, std::span<const uint32_t> indices);
double mesh_area(std::span<const Vec3> positions, std::span<const uint32_t> indices);
Aabb mesh_bounds(std::span<const Vec3> positions);

// Area-weighted vertex normals (unit length; zero for unreferenced vertices).
std::vector<Vec3> vertex_normals(std::span<const Vec3> positions, std::span<const uint32_t> indices);

}  // namespace body
