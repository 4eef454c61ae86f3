#pragma once
// Vertex-cache order of a triangle list in place, in bounded memory: the
// triangles sorted along a Morton curve of their first corner's cell (an
// in-place bucket sort), then runs of about kOrderWindowFaces consecutive
// triangles each through pm::cache_order_window's in-place form (shared with
// the decoder's batch order, shared/pm/cache_window.h). The scratch is that of one window plus one
// entry a vertex, not meshoptimizer's whole-mesh tables and a second copy
// (about 3x the index bytes for a 1.1M-triangle level; bench/RESULTS.md).
// Used by level_order.h on the mapped element buffer itself.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>

namespace body::render {

// Triangles per meshoptimizer window.
inline constexpr size_t kOrderWindowFaces = 32768;
// Cells of vertex_cells: 32 per axis, a 15-bit Morton code.
inline constexpr uint32_t kOrderCellBits = 15;

// The Morton cell (kOrderCellBits bits, 5 per axis) of the point at `t`
// (each axis in [0, 1] within the model's box; clamped).
uint16_t order_cell(float tx, float ty, float tz);

// Orders the triangles of `indices` (3 per triangle, each < cells.size();
// cells[v] = order_cell of vertex v) for the vertex cache, in place, each
// triangle's corners as they were. `cancel` (may be null) is polled between
// buckets and windows. Returns false when the input is bad (not a whole
// number of triangles, an index past the cells: `indices` untouched) or when
// cancelled (`indices` then holds the same triangles in some order).
bool order_in_windows(std::span<uint32_t> indices, std::span<const uint16_t> cells,
                      const std::atomic<bool>* cancel = nullptr, size_t window_faces = kOrderWindowFaces);

}  // namespace body::render
