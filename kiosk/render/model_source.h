#pragma once
// Model files for the renderer: `.bpm` progressive meshes (shared/pm) and plain
// Wavefront OBJ, one ModelSource per structure/object, each able to go to a
// level of detail and hand the renderer the arrays plus the dirty ranges.
//
//   auto sources = load_model_file("brain.bpm");      // or .obj
//   src.set_lod(0.4);                                  // 40% of the full triangles
//   renderer.add_model(src.mesh(), src.name());        // first upload (capacity = full)
//   src.set_lod(0.1); renderer.update_model(id, src.mesh(), src.take_dirty());
//
// LOD: for `.bpm` the progressive mesh's vertex splits (prefix arrays, index
// patches as dirty ranges). OBJ files have no LOD hierarchy; set_lod() on one
// falls back to a meshoptimizer simplification of the whole index array (a
// preview path only: convert with `bodygen` to get progressive meshes).
#include <memory>
#include <string>
#include <vector>

#include "kiosk/render/renderer.h"
#include "shared/error.h"
#include "shared/pm/progressive_mesh.h"

namespace body::render {

class ModelSource {
public:
    // A plain mesh (OBJ object or a generated one).
    ModelSource(std::string name, Vec3f color, std::vector<Vec3f> positions, std::vector<Vec3f> normals,
                std::vector<uint32_t> indices);
    // A progressive mesh at its finest decoded level.
    explicit ModelSource(std::unique_ptr<pm::ProgressiveMesh> pm);

    const std::string& name() const { return name_; }
    Vec3f color() const { return color_; }
    bool progressive() const { return pm_ != nullptr; }
    size_t full_triangles() const;
    size_t triangles() const;  // at the current level
    // Ratio of full_triangles() in (0, 1]; values outside are clamped.
    void set_lod(double ratio);
    // Current arrays and drawn counts.
    MeshData mesh() const;
    // Ranges changed since the last call (everything on the first call).
    Dirty take_dirty();

private:
    std::string name_;
    Vec3f color_{0.8f};
    std::unique_ptr<pm::ProgressiveMesh> pm_;
    std::vector<Vec3f> positions_, normals_;
    std::vector<uint32_t> full_indices_, indices_;  // OBJ: full and (when simplified_) current indices
    bool simplified_ = false;
    std::span<const uint32_t> current_indices() const { return simplified_ ? indices_ : full_indices_; }
    bool first_ = true;
    Dirty pending_;
};

// Loads `.bpm` or `.obj` (by extension); errors name the file and the reason.
Result<std::vector<ModelSource>> load_model_file(const std::string& path);

}  // namespace body::render
