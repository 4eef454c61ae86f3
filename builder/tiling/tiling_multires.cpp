// Multiresolution tiling: placeholder (greedy) until FKU lands.
#include "builder/tiling/tiling_internal.h"

namespace body {
void tile_greedy(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles);
void tile_multires(std::span<const Vec3> lower, std::span<const Vec3> upper, std::vector<uint32_t>& triangles) {
    tile_greedy(lower, upper, triangles);
}
}  // namespace body
