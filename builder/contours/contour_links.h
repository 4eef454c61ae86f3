#pragma once
// The "links" section of `*.contours.json`: the reviewer's correspondence
// overrides (cut, join, exclude; format in contour_stack.h), read from the
// JSON value the stack reader captured, checked against the merged stack, and
// written back with references to the written slice and contour positions.
//
// Errors are one line: "PATH: links entry N: slice S contour C: no such
// contour", "PATH: links entry N: slice S contour C and slice S' contour C'
// are not on adjacent slices (z = a and b)", "PATH: links entry N: join of
// contours of different structures ('a' and 'b')", or the entry's shape.
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "shared/error.h"

namespace body {

// The entries of a "links" value, in file order (shape only).
Result<std::vector<LinkOverride>> parse_link_overrides(const nlohmann::json& links, const std::string& path);

// Every reference of stack.links names a contour of the (merged, sorted)
// stack; a cut or join joins adjacent slices; a join stays within one
// structure label (unlabelled contours may join anything unlabelled).
Status check_link_overrides(const ContourStack& stack, const std::string& path);

// stack.links as a "links" value whose references are positions in
// stack.slices (what contour_stack_to_json writes); entries naming no contour
// of the stack are left out.
nlohmann::json link_overrides_to_json(const ContourStack& stack);

// Where `ref` is in the merged stack: slice and position, or nullopt.
struct ContourPlace {
    size_t slice = 0, position = 0;
};
std::optional<ContourPlace> find_contour(const ContourStack& stack, const ContourRef& ref);

}  // namespace body
