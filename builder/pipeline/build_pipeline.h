#pragma once
// The whole contour-stack -> mesh pipeline, one structure at a time:
//   validate & repair (contours/validate.h) -> group unlabelled contours into
//   structures -> per structure: nesting (solid/hole), correspondence between
//   adjacent slices (correspondence/), bands (tiling/), branches (branching/),
//   caps (caps/) -> one closed mesh per structure with its statistics.
//
// Branches (1:N, N:1): when every branch lies inside the single contour the
// region between them is triangulated as a lifted planar height field between
// two short vertical walls; otherwise the single contour is split by nearest-
// branch partition with bisector chords (branching/); failing that (the
// construction would cross itself), a mid-slice ring around the union of the
// group's regions takes N:1 below and 1:M above as such height fields; then the
// partition with interior side branches detached (closed by their own caps);
// last the convex hull instead of the union ring. N:M goes through the union
// ring (or the hull). A 1:1 pair where a hole on one slice opens into a notch
// of the other slice's contour splits that contour between the solid and the
// hole. Contours linked to nothing become thin slabs around their plane.
//
// Guarantees for valid input with the default options (partition branching,
// dome or flat caps): every mesh is closed, consistently oriented outward and
// vertex- and edge-manifold, without degenerate triangles; re-slicing just
// above or below each input plane gives back its contours. Bands come from
// tiling/ and are only as fold-free as it makes them; branch geometry is built
// to avoid crossings but not proven free of them for every input.
// `--branching overlap` (thesis method) and `--caps none` leave open or
// overlapping surfaces by design. Interpolation (`interpolate` > 0) keeps
// every guarantee above: traced points and contour edges stay, curves that
// would make triangles meet are left straight. Smoothing (`fairing.iterations` > 0) keeps the
// connectivity, hence closedness and manifoldness, but not the re-slicing property.
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "builder/branching/branching.h"
#include "builder/caps/caps.h"
#include "builder/contours/contour_stack.h"
#include "builder/contours/validate.h"
#include "builder/correspondence/correspondence.h"
#include "builder/fairing/fairing.h"
#include "builder/tiling/tiling.h"
#include "shared/error.h"
#include "shared/mesh.h"

namespace body {

struct BuildOptions {
    // The defaults are the most accurate choices measured (bench/RESULTS.md).
    CapStyle caps = CapStyle::Dome;
    TilingMethod tiling = TilingMethod::Multires;
    CorrespondenceMethod correspondence = CorrespondenceMethod::Overlap;
    BranchingMethod branching = BranchingMethod::Partition;
    // Optional Taubin smoothing of each finished mesh (off by default: it moves
    // vertices off their slice planes; see fairing/fairing.h).
    FairingOptions fairing;
    // Intermediate rings per slice gap on C1 Hermite curves through the traced
    // contours (fairing/slice_interpolation.h); 0 keeps the linear bands.
    // Above 0 the domes' chords are lifted too (caps/caps.h).
    int interpolate = 0;
    // Each rung's points: the fewest, at most `interpolate`, keeping its curve
    // within this fraction of the slice gap of their polyline; 0: all of them.
    // The default is the largest measured that keeps, on the bench stacks,
    // the area-sampled mean distance to the true surface within 1 % of every
    // rung taking `interpolate` points and the Hausdorff distance the same,
    // with 16-24 % fewer triangles (bench/RESULTS.md).
    double ring_tolerance = 0.004;
    // For a stack that knows its voxel (ContourStack::voxel: label volumes),
    // no points where a curve stays within this fraction of a voxel of its
    // chord: the contours are traced to about a voxel, so finer bends add
    // triangles, not detail. 0: the gap rule alone. `bodygen build` and
    // `exhibit` pass 0.25 (bench/RESULTS.md).
    double ring_voxel = 0.0;
    // Threads (the output does not depend on it): structures built at once
    // (they are independent); threads left over when there are fewer
    // structures than jobs search each structure's interpolated mesh for
    // meeting triangles (`interpolate` > 0) a few slabs at a time.
    unsigned jobs = 1;
    // Called after each slice of each structure: (done, total) slices. With
    // jobs > 1 it is called from the worker threads, one call at a time.
    std::function<void(size_t done, size_t total)> progress;
    // Contour repair (contours/validate.h): strict refusal or the repair tolerance.
    RepairOptions repair;
    // Receives repair warnings (duplicate points removed, keyholes split, ...),
    // one line each, before any structure is built.
    std::function<void(const std::string& message)> warning;
    // Receives the repair counts by kind (RepairLog::counts) when set.
    std::function<void(const std::map<std::string, size_t>& counts)> repair_counts;
};

struct StructureMesh {
    Mesh mesh;            // name and colour from the stack's structure (or an automatic one)
    std::string id;       // structure id ("auto_N" for unlabelled groups)
    size_t contours = 0;  // input contours in this structure
    size_t triangles = 0;
    double volume = 0.0;  // signed, positive for outward orientation (units^3)
    double area = 0.0;    // units^2
    long genus = 0;       // sum over components; meaningful when closed_manifold
    size_t components = 0;
    bool closed_manifold = false;
    size_t fairing_restored = 0;            // vertices smoothing left in place to avoid a self-intersection
    size_t interpolation_straightened = 0;  // rungs interpolation left straight to avoid a self-intersection
    double seconds = 0.0;                   // wall time spent on this structure
};

// Builds one mesh per structure that has contours. Errors name `source_path`,
// the slice/contour indices of the input file and the reason (exit code 2 for
// bad input, 1 for a failure of the builder itself).
Result<std::vector<StructureMesh>> build_structures(const ContourStack& stack, const BuildOptions& options,
                                                    const std::string& source_path);

}  // namespace body
