#pragma once
// The key of the undirected edge (a, b): the smaller vertex in the high 32
// bits, so (a, b) and (b, a) give the same key, and keys order edges by their
// smaller then larger vertex.
#include <algorithm>
#include <cstdint>

namespace body {

inline uint64_t edge_key(uint32_t a, uint32_t b) { return uint64_t(std::min(a, b)) << 32 | std::max(a, b); }

}  // namespace body
