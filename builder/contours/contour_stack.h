#pragma once
// The contour stack: planar closed polygons traced on parallel slices.
//
// File format `*.contours.json` (format "bodygen.contours", version 1):
//   {"format": "bodygen.contours", "version": 1, "units": "mm",
//    "structures": [{"id": "kidney_l", "name": "Left kidney", "color": [0.8, 0.3, 0.3]}],
//    "slices": [{"z": 12.5, "contours": [{"points": [[x, y], ...], "structure": "kidney_l"}]}]}
// A contour is closed (last point not repeated), of arbitrary orientation.
// Slices may come in any order and spacing; slices whose z differ by less
// than kSliceMergeTolerance are one slice.
#include <cstddef>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/geometry.h"

namespace body {

inline constexpr double kSliceMergeTolerance = 1e-3;

struct Contour {
    std::vector<Vec2> points;
    std::string structure;      // structure id; empty when unlabelled
    size_t source_slice = 0;    // index of the slice in the input file (for messages)
    size_t source_contour = 0;  // index of the contour within that input slice
};

struct Slice {
    double z = 0.0;
    std::vector<Contour> contours;
    size_t source_index = 0;  // first input slice merged into this one
};

struct StructureInfo {
    std::string id;
    std::string name;
    Vec3 color{0.8, 0.8, 0.8};
};

struct ContourStack {
    std::string units = "mm";
    std::vector<StructureInfo> structures;
    std::vector<Slice> slices;  // sorted by increasing z after reading
};

// Parses a contour stack. Errors name `path`, the slice/contour index in the
// file and the reason. Slices are merged (|dz| < tolerance) and sorted by z;
// contours keep their source indices. Structure references must exist.
Result<ContourStack> parse_contour_stack(const std::string& json_text, const std::string& path);
Result<ContourStack> read_contour_stack(const std::string& path);

// Serialises a stack (atomically when writing to a file).
std::string contour_stack_to_json(const ContourStack& stack);
Status write_contour_stack(const std::string& path, const ContourStack& stack);

}  // namespace body
