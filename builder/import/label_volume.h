#pragma once
// The NIfTI label importer's pieces shared by its files (nifti_import.cpp:
// reading, slicing, voxel faces; label_smooth.cpp: the --label-smooth route).
// Internal to builder/import.
#include <cstddef>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "builder/import/import.h"
#include "shared/geometry.h"

namespace body::label_import {

// A label volume read whole: int32 labels, x fastest.
struct LabelVolume {
    size_t dim[3] = {1, 1, 1};
    double affine[3][4] = {};             // voxel index (i, j, k, 1) -> scanner mm
    double spacing[3] = {1.0, 1.0, 1.0};  // mm between voxel centres along each voxel axis
    std::vector<int32_t> labels;
    size_t index(size_t i, size_t j, size_t k) const { return (k * dim[1] + j) * dim[0] + i; }
};

// The output frame of a slicing axis (see import.h).
struct SliceFrame {
    int axis = 2, u = 0, v = 1;  // voxel axes: slice normal, in-plane x, in-plane y
    Vec3 e1, e2, n;              // output x, y, z directions in scanner space
    Vec3 col[3], origin;
    bool oblique = false;

    Vec3 scanner(double i_u, double i_v, double k) const {
        return origin + col[u] * i_u + col[v] * i_v + col[axis] * k;
    }
    Vec2 in_plane(double i_u, double i_v, double k) const {
        const Vec3 p = scanner(i_u, i_v, k);
        return {glm::dot(e1, p), glm::dot(e2, p)};
    }
    double z(double k) const { return glm::dot(n, scanner(0.0, 0.0, k)); }
};

// A label's bounding box in voxel indices and its voxel count.
struct Extent {
    size_t lo[3] = {SIZE_MAX, SIZE_MAX, SIZE_MAX};
    size_t hi[3] = {0, 0, 0};
    size_t voxels = 0;
};

struct LabelResult {
    int64_t label = 0;
    std::vector<std::pair<size_t, std::vector<std::vector<Vec2>>>> slices;  // slice index -> rings (output frame)
};

// One slice's rings: specks dropped, simplified, into the output frame.
// (u0, v0) is the voxel index of the traced grid's pixel (0, 0).
void finish_rings(const SliceFrame& f, double u0, double v0, size_t k, const ImportOptions& o,
                  std::vector<std::vector<Vec2>>& rings, LabelResult& out);

// A label's traced rings, per traced slice (slice index, rings in the traced
// plane's pixels, inside on the left), slices `step` apart where adjacent:
// rings on adjacent slices whose regions meet are joined (solids with solids,
// holes with holes), and each group whose volume (|ring area| x step, in
// voxels) stays under `min_volume` is dropped, except the largest group of
// solids (ring_islands.cpp). Solids are the rings whose signed area times
// `solid_sign` is positive, holes the others.
void drop_small_islands(std::vector<std::pair<size_t, std::vector<std::vector<Vec2>>>>& traced, size_t step,
                        double min_volume, double solid_sign = 1.0);

// The same for a label's finished rings (in the output frame): groups under
// `min_voxels` voxels dropped, the largest group of solids kept.
void drop_small_islands(const SliceFrame& f, const ImportOptions& o, double min_voxels, LabelResult& out);

// Pieces of a label under this many voxels are specks the full blur removes
// (--label-smooth): they and groups of rings under it are dropped.
constexpr size_t kMinPiece = 20;

// --label-smooth (label_smooth.cpp). Smoothing levels: 0 the full width,
// each next one half of it (s, s/2, s/4).
constexpr int kSmoothLevels = 3;

// Blur widths per voxel axis for --label-smooth s at `level`: s voxels of the
// finest axis, the same in millimetres on every axis.
void axis_sigmas(const LabelVolume& vol, double s, int level, double out[3]);

// How a label is smoothed: its level, the gain its blurred indicator is
// scaled by where it is compared with its neighbours (levels > 0), and the
// weight c of the blurred background in its full-width field f + c * bg.
struct ThinLabel {
    int level = 0;
    float gain = 1.0f;
    float c = 0.0f;
};

// The background's indicator (label 0, and 1 beyond the volume) blurred by
// the full width once for all labels: over `labelled` (the union of the
// labels' extents) padded by twice the blur's radius on each axis, so every
// label's working box lies inside it.
// Wherever a label's field can reach its level (within one radius of the
// label) the taps of this blur and of the box's own blur are the same voxels,
// summed in the same order: the values there are the same floats. Memory:
// one float per voxel of that padded box.
struct BackgroundBlur {
    long lo[3] = {0, 0, 0};  // volume index of the field's voxel (0, 0, 0)
    size_t size[3] = {0, 0, 0};
    std::vector<float> field;  // x fastest
};
BackgroundBlur blur_background(const LabelVolume& vol, const Extent& labelled, double s);

// Pass 1, one label: traced on its blur by the full width (final unless a
// thin label is near). Returns how the label is to be smoothed: level 0 when
// the full width keeps at least 90 % of its voxel centres and does not split
// it, else the first narrower level that would.
ThinLabel extract_label_smoothed(const LabelVolume& vol, const SliceFrame& fr, int32_t label, const Extent& e,
                                 const ImportOptions& o, const BackgroundBlur& bg, LabelResult& out);

// Pass 2, one label that is thin (`own.level > 0`) or has a thin label within
// its working box, `own` as pass 1 returned it and `out` as pass 1 traced it:
// traced again against the thin labels' own blurs, overlap-free (see
// label_smooth.cpp). A thin label's slices are all replaced; another label's
// only those within reach of a thin label's blur.
void extract_label_among_thin(const LabelVolume& vol, const SliceFrame& fr, int32_t label, const Extent& e,
                              const ImportOptions& o, const ThinLabel& own, const std::map<int32_t, ThinLabel>& thin,
                              const BackgroundBlur& bg, LabelResult& out);

// Whether a thin label other than `label` has a voxel within its working box.
bool box_meets_thin(const LabelVolume& vol, const Extent& e, int32_t label, const std::map<int32_t, ThinLabel>& thin,
                    double s);

}  // namespace body::label_import
