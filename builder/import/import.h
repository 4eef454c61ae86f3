#pragma once
// Segmentations in: NIfTI label volumes and DICOM RT-STRUCT -> contour stacks.
//
// Conventions (the contract with the reconstruction pipeline):
// - Units are millimetres in scanner space. NIfTI voxel indices map through the
//   sform when sform_code > 0, else the qform when qform_code > 0, else the
//   pixdim scaling (NIfTI "method 1").
// - Slicing along voxel axis `axis` (0 = i/x, 1 = j/y, 2 = k/z) takes every
//   `step`-th voxel plane, starting at index 0. A slice lies on the plane
//   through its voxel centres. When that plane is perpendicular to a scanner
//   axis A (the usual case), the stack's (x, y, z) are the scanner coordinates
//   cyclically permuted so that z is A: A = z -> (x, y, z), A = x -> (y, z, x),
//   A = y -> (z, x, y) -- a rotation, so meshes keep their handedness. An
//   oblique plane gets a rigid frame with z along its normal (a note says so).
// - In-plane, the boundary lies on the voxel faces (marching squares with
//   vertices halfway between an inside and an outside voxel centre, see
//   marching_squares.h), so a contour encloses its voxels' cross-section up to
//   1/8 voxel per convex corner cut (and gained per concave corner): for a
//   simple region the area is the voxel count minus 1/2 voxel, exactly, before
//   simplification. Along the slice axis the surface convention is up to the
//   pipeline's caps: the voxels of a region span half a voxel beyond its first
//   and last slice planes.
// - With label_smooth > 0 the contours follow the 0.5 level of f + c * bg
//   instead, f the label's indicator and bg the background's (label 0 and
//   beyond the volume), both blurred (label_smooth voxels of the finest axis,
//   the same in millimetres on every axis): between voxel centres, changing
//   gradually from slice to slice. c (0-0.45 per label) is the least that
//   puts as many voxel centres above 0.5 as the label has voxels. Blurred
//   indicators of disjoint labels and the background sum to 1, so two labels'
//   regions cannot overlap (up to the linear interpolation inside a cell and
//   the simplification). A label that this would shrink below 90 % of its
//   voxel centres or split (thin parts, bridges enclosed by other labels) is
//   blurred less (half or a quarter), scaled to keep its voxel area, and
//   it and the labels around it compared blur against blur at the narrower
//   width of each pair: still no overlap (label_smooth.cpp).
// - Diagonal-only pixel contacts are not connections (4-connected regions per
//   label), consistently for every label, so regions of different labels never
//   overlap and the rings of one structure on a slice never touch or cross,
//   simplified or not.
// - Structures are emitted in increasing label order, contours on a slice by
//   structure then by ring; the result does not depend on `jobs`.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "shared/error.h"

namespace body {

struct ImportOptions {
    std::string labels_path;          // label table; empty: look for <volume>.txt/.lut beside the volume
    int axis = 2;                     // 0 x, 1 y, 2 z (voxel axes)
    int step = 1;                     // every step-th slice
    std::vector<int64_t> only;        // labels to extract; empty: all present
    std::optional<double> threshold;  // binarise: value >= threshold is label 1
    double tolerance = 0.5;           // simplification tolerance in voxels (0: none)
    // Islands and holes whose traced area is below this many voxel cross-sections
    // are dropped (holes filled): per-slice speckle cleanup, 0 keeps everything.
    // At most 8, so no dropped island can contain a hole.
    double min_area = 0.0;
    // Sub-voxel contours: each label's indicator blurred in 3-D by a Gaussian
    // of this standard deviation (voxels of the finest axis, 0-4), traced as above with linear
    // interpolation along cell edges (gaussian_blur.h, trace_field_isolines in
    // marching_squares.h). 0: the voxel-face boundary described above.
    double label_smooth = 0.0;
    int jobs = 1;  // worker threads across structures
    // Called from the calling thread as structures finish: (done, total).
    std::function<void(size_t, size_t)> progress;
    // Non-fatal findings (skipped contours, oblique frames, empty labels).
    std::function<void(const std::string&)> note;
};

enum class SourceKind { ContourStack, Nifti, RtStruct, Unknown };

// By extension (.contours.json/.json, .nii/.nii.gz/.hdr/.img) and, for DICOM,
// the "DICM" preamble or a .dcm extension.
SourceKind detect_source_kind(const std::string& path);

// A structure id from a display name: every character other than a letter,
// digit, '_', '-' or '.' becomes '_'.
std::string structure_id_from_name(const std::string& name);

Result<ContourStack> import_nifti_labels(const std::string& path, const ImportOptions& options);
Result<ContourStack> import_rtstruct(const std::string& path, const ImportOptions& options);

// Dispatch for `bodygen build` and `bodygen contours`: a contour stack file is
// read as is; label volumes and RT-STRUCTs are imported.
Result<ContourStack> load_any_contour_source(const std::string& path, const ImportOptions& options);

}  // namespace body
