#pragma once
// One window of triangles in vertex-cache order: the kernel under the kiosk's
// settled-level order (kiosk/render/window_order.h, bounded memory), in place
// over a mapped element buffer or, resumable in slices, as a permutation of face
// numbers (which must match the in-place form bit for bit). Both first sort
// their triangles along a Morton curve of each triangle's first corner
// (morton_code; the decoder's per-batch order, draw_order.h, is that sort
// alone), then cut that order into windows of whole Morton cells of about 8K
// triangles and order each window here: the window's vertices numbered among
// themselves in the order its triangles first use them, then
// meshopt_optimizeVertexCache over those numbers (its tables sized by the
// window, not the mesh).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace body::pm {

// The Morton code of a point's cell: bits 0..9 of x, y and z interleaved
// (x in bits 0, 3, 6, ...; y one above, z two above); higher bits ignored.
// Inline: the decoder's sort calls it once a face.
constexpr uint32_t morton_spread3(uint32_t x) {  // bits 0..9 of x to every third bit
    x &= 0x3ff;
    x = (x | (x << 16)) & 0x30000ff;
    x = (x | (x << 8)) & 0x300f00f;
    x = (x | (x << 4)) & 0x30c30c3;
    x = (x | (x << 2)) & 0x9249249;
    return x;
}
inline uint32_t morton_code(uint32_t x, uint32_t y, uint32_t z) {
    return morton_spread3(x) | morton_spread3(y) << 1 | morton_spread3(z) << 2;
}

// Working memory of the window kernels, caller-owned and reused between
// windows. Its contents belong to the kernels: local_of stays all UINT32_MAX
// between calls and must be at least one entry per vertex any window uses;
// local, global and sorted at least 3 entries per triangle of the largest
// window (reserve_cache_window sizes them). The permutation form grows start,
// by_first and window itself.
struct CacheWindowScratch {
    std::vector<uint32_t> local_of;  // a vertex's window-local number, UINT32_MAX outside
    std::vector<uint32_t> local, global, sorted, start, by_first, window;
};

// Sizes `s` for windows of up to `window_faces` triangles over vertices
// below `vertex_count` (only growing; new local_of entries UINT32_MAX).
void reserve_cache_window(CacheWindowScratch& s, size_t window_faces, size_t vertex_count);

// Permutation form: reorders the face numbers faces[0 .. n) (each face f has
// its corners at indices[3 f .. 3 f + 3)) into vertex-cache order. The faces
// themselves are untouched; each output triangle is the input face with the
// same three corners in the same order (the first unused one among equal
// faces), so the result is a permutation of the input for any input. Returns
// false (faces[] as it was) only should meshoptimizer emit a triangle that is
// not among its input. `s` reserved for n faces and every vertex used.
bool cache_order_window(const uint32_t* indices, uint32_t* faces, size_t n, CacheWindowScratch& s);

// In-place form: the n triangles triples[0 .. 3 n) rewritten in vertex-cache
// order, each triangle's corners as they were (meshoptimizer emits its input
// triangles corner for corner). Same order as the permutation form with
// faces = 0 .. n-1, without its matching scratch. `s` reserved as above.
void cache_order_window(uint32_t* triples, size_t n, CacheWindowScratch& s);

}  // namespace body::pm
