#pragma once
// The contour stack: planar closed polygons traced on parallel slices.
//
// File format `*.contours.json` (format "bodygen.contours", version 1 or 2):
//   {"format": "bodygen.contours", "version": 2, "units": "mm",
//    "structures": [{"id": "kidney_l", "name": "Left kidney", "color": [0.8, 0.3, 0.3]}],
//    "slices": [{"z": 12.5, "contours": [{"points": [[x, y], ...], "structure": "kidney_l"}]}],
//    "links": [{"cut": [[0, 1], [1, 0]]}, {"join": [[1, 0], [2, 1]]}, {"exclude": [3, 0]}]}
// A contour is closed (last point not repeated), of arbitrary orientation.
// Slices may come in any order and spacing; slices whose z differ by less
// than kSliceMergeTolerance are one slice.
// Version 2 adds "links", the reviewer's correspondence overrides (optional;
// version 1 files are read as before and have none). Each entry names
// contours as [slice, contour], their indices in the file's arrays:
//   "cut": [A, B]   no link between A and B (on adjacent slices), whatever
//                   the correspondence computes;
//   "join": [A, B]  A and B (adjacent slices, same structure) are linked
//                   even if the correspondence does not link them;
//   "exclude": A    A is left out of the build.
// Entries apply in file order (a later one wins over an earlier one on the
// same pair). Correspondence matches solid boundaries with solids and holes
// with holes, so a join of a solid and a hole links nothing.
// A cut or join between contours that are not on adjacent slices (after the
// merging below), or a reference to no contour, is refused when reading.
// Writers emit version 1 when there are no links, so such files stay readable
// by older builders.
// "voxel" (optional, either version; a positive number in the stack's units):
// the in-plane voxel size of the label volume the contours were traced from
// (`bodygen contours` writes it), so a build from the file bounds its rings as
// a build from the volume does. Older readers ignore it, as any unknown member.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "shared/error.h"
#include "shared/geometry.h"

namespace body {

inline constexpr double kSliceMergeTolerance = 1e-3;

// Coordinates (x, y and slice z) must lie within +-kMaxCoordinate (10 km in
// mm): far beyond any body, and small enough that products of coordinate
// differences (areas, cross products, squared distances) stay finite, so no
// NaN or infinity can reach an index in caps or tiling.
inline constexpr double kMaxCoordinate = 1e7;

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

// A contour as the file names it: its slice's index in "slices" and its own
// index in that slice's "contours" (Contour::source_slice / source_contour).
struct ContourRef {
    size_t slice = 0, contour = 0;
    bool operator==(const ContourRef&) const = default;
    auto operator<=>(const ContourRef&) const = default;
};

// One correspondence override of the "links" section.
enum class LinkEdit : uint8_t { Cut, Join, Exclude };
struct LinkOverride {
    LinkEdit edit = LinkEdit::Cut;
    ContourRef a, b;  // b: cut and join only
    bool operator==(const LinkOverride&) const = default;
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
    // Unit directions of the stack's +x, +y, +z in RAS+ patient space (x toward
    // the patient's right, y anterior, z superior) when the source says so (label
    // volumes, RT-STRUCTs); not stored in stack files. Orients exhibits' cameras.
    std::optional<std::array<Vec3, 3>> ras_axes;
    // A label volume's in-plane voxel size (the larger of its two; stack
    // units): its contours are traced only to within about that. Set by the
    // label import; stored in stack files as "voxel".
    std::optional<double> voxel;
    // The "links" section, in file order; references are file indices.
    std::vector<LinkOverride> links;
};

// Whether `c` is (or, after repairs split it, comes from) the contour `ref` names.
inline bool names(const ContourRef& ref, const Contour& c) {
    return c.source_slice == ref.slice && c.source_contour == ref.contour;
}

// Contours and points in a stack, over all slices (for summaries).
struct StackCounts {
    size_t contours = 0, points = 0;
};
inline StackCounts count_contours(const ContourStack& stack) {
    StackCounts n;
    for (const Slice& s : stack.slices) {
        n.contours += s.contours.size();
        for (const Contour& c : s.contours) n.points += c.points.size();
    }
    return n;
}

// Parses a contour stack. Errors (exit code 2) are one line naming `path`, the
// place in the file and the reason: "PATH: slice S contour C: point K must be
// [x, y]"; a number too large for a double (1e999) as "PATH: slice S contour C:
// point K is not finite (number overflow at byte B: '1e999')"; a syntax error or
// truncation as "PATH: byte B: invalid JSON at slice S contour C point K: why".
// B counts bytes read, as nlohmann does: the 1-based index of the offending
// token's last byte, or one past the end of a file that stops early. With
// several problems the reported one is: syntax, format, version, units,
// structures, then the first bad slice/contour/point in file order.
// Slices are merged (|dz| < tolerance) and sorted by z; contours keep their
// source indices. Structure references must exist. Members may come in any
// order; unknown members are ignored.
// Parsing streams (SAX, no document tree): memory is the stack itself plus
// the longest token; read_contour_stack reads the file through a 1 MiB buffer
// instead of loading it.
// Coordinates outside +-kMaxCoordinate are refused: "PATH: slice S contour C:
// point K (x, y) is outside the coordinate range +-1e7" or "PATH: slice S: z
// = Z is outside ..." (S, C: source indices).
Result<ContourStack> parse_contour_stack(const std::string& json_text, const std::string& path);
Result<ContourStack> read_contour_stack(const std::string& path);

// The range check above for a stack from any source (imports, slicing).
Status check_coordinate_range(const ContourStack& stack, const std::string& path);

// Serialises a stack (atomically when writing to a file). Slices are written
// in the stack's (sorted, merged) order, so the links' references are
// rewritten to the written indices.
std::string contour_stack_to_json(const ContourStack& stack);
Status write_contour_stack(const std::string& path, const ContourStack& stack);

}  // namespace body
