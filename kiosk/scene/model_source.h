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
//
// Plain meshes are reordered at load (triangles in vertex-cache order,
// vertices renumbered in the order the triangles first use them): the same
// surface, other numbers. Memory: positions are kept as 16-bit codes in their
// box (the renderer's format), and the full index array compressed
// (meshoptimizer's index codec, 3-5 bytes a triangle instead of 12), which is
// what set_lod() simplifies from; the current level's plain array is needed
// only until the renderer has it, and release_arrays() frees it (mesh()
// decodes it again if asked):
//   renderer.update_model(id, src.upload_mesh(), src.take_dirty());  src.release_arrays();
#include <memory>
#include <string>
#include <vector>

#include "kiosk/render/renderer.h"
#include "shared/error.h"
#include "shared/pm/progressive_mesh.h"

namespace body::kiosk {

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
    // Current arrays and drawn counts (float positions and, for progressive
    // meshes, normals decoded from the kept codes when first asked for, plus
    // the codes themselves).
    render::MeshData mesh() const;
    // The same for an upload: positions as codes only (render::MeshData::position_codes)
    // and a progressive mesh's normals as its octahedral codes
    // (render::MeshData::normal_codes), so no float copy is made. A complete
    // progressive mesh with normals hands its index array over to the
    // add_model it goes to: packed in place now, it fills the new element
    // buffer and is freed (render::MeshData::index_fill; see release_arrays() for what
    // follows).
    render::MeshData upload_mesh() const;
    // Ranges changed since the last call (everything on the first call).
    render::Dirty take_dirty();
    // Plain meshes: frees the current level's index array and the float
    // positions once uploaded (the renderer keeps its own copy); a later
    // mesh() decodes them again from the codes, with the same triangles (a
    // triangle's corners may come rotated, its winding kept). Progressive
    // meshes: the floats mesh() decoded (their splits patch the codes in
    // place) and, once every split is decoded and when the file has normals,
    // the index array and the vertex data for good (pm::ProgressiveMesh::
    // release_indices, ::release_vertex_data; upload_mesh() already hands the
    // index array over to add_model, freeing it as it goes up): the renderer's
    // buffers become the only copy, upload_mesh() then carries the level's
    // patches (render::MeshData::index_patch, ::position_patch) instead of arrays, and
    // mesh() has none. Call it only after add_model(upload_mesh()) of one
    // renderer model, and use upload_mesh() for every later update of it.
    void release_arrays();

private:
    enum class Decoded : uint8_t { None, Full, Level };
    std::string name_;
    Vec3f color_{0.8f};
    std::unique_ptr<pm::ProgressiveMesh> pm_;
    std::vector<Vec3f> normals_;
    // Plain meshes: positions as 16-bit codes in [box_min_, box_max_] (3 per
    // vertex, as a .bpm keeps them; the renderer draws the same codes), and
    // as floats while positions_decoded_ (until release_arrays()).
    std::vector<uint16_t> position_codes_;
    Vec3f box_min_{0.0f}, box_max_{0.0f};
    size_t vertex_count_ = 0;
    mutable std::vector<Vec3f> positions_, pm_normals_;  // pm_normals_: a progressive mesh's, decoded
    mutable bool positions_decoded_ = false;
    std::span<const Vec3f> positions() const;  // decodes when released
    // Plain meshes: the full level and (when simplified_) the current level's
    // indices, compressed; indices_ holds the level named by decoded_.
    std::vector<uint8_t> full_code_, level_code_;
    size_t full_index_count_ = 0, level_index_count_ = 0;
    bool simplified_ = false;
    mutable std::vector<uint32_t> indices_;
    mutable Decoded decoded_ = Decoded::Full;
    size_t current_index_count() const { return simplified_ ? level_index_count_ : full_index_count_; }
    std::span<const uint32_t> current_indices() const;  // decodes the current level when released
    bool first_ = true;
    render::Dirty pending_;
    // A complete progressive mesh with normals, its index array still its own.
    bool hands_over_indices() const;
    render::MeshData upload_mesh_of(bool hand_over) const;  // hand_over: upload_mesh(), else mesh()
};

// The renderer's view of a progressive mesh at its current level: its own
// codes (positions in its box, octahedral normals), no float copy. Once the pm
// has handed arrays to the renderer (released or packed indices, released
// vertex data), also the hooks that write its pending patches (or fill the
// packed array) into the renderer's buffers; they refer to `pm`, which must
// outlive the render::MeshData.
render::MeshData mesh_data_of(pm::ProgressiveMesh& pm);

// Loads `.bpm` or `.obj` (by extension); errors name the file and the reason.
Result<std::vector<ModelSource>> load_model_file(const std::string& path);

}  // namespace body::kiosk
