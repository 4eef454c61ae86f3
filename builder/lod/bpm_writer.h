#pragma once
// The `.bpm` writer: meshes -> progressive meshes (simplify.h) -> a file image
// (format: shared/pm/FORMAT.md). One structure per mesh; all structures' INFO
// and BASE sections first, then their SPLT chunks interleaved, so every structure
// is drawable early while a file streams in. The bytes are the same on every
// platform and for any LodOptions::threads.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "builder/lod/simplify.h"
#include "shared/error.h"
#include "shared/mesh.h"
#include "shared/pm/split_codec.h"

namespace body::lod {

// Serializes meshes (one structure each: name, colour, bounds) as a .bpm file image.
// `sizes`, when given, gets where the SPLT sections' bytes went (all structures).
Result<std::vector<uint8_t>> encode_bpm(std::span<const Mesh> meshes, const LodOptions& options = {},
                                        pm::SplitSizes* sizes = nullptr);
// Builds the progressive meshes and writes them atomically to `path`.
Status write_bpm_from_meshes(const std::string& path, std::span<const Mesh> meshes, const LodOptions& options = {},
                             pm::SplitSizes* sizes = nullptr);

}  // namespace body::lod
