#pragma once
// Grouping: which contours make one structure, and which linked contours
// between two slices are joined by one construction.
//
// Structures: labelled contours go to their structure (the stack's order);
// unlabelled ones are grouped by correspondence of their outermost contours
// across slices (by the whole area each encloses; every nested contour follows
// its parent) into structures "auto_1", "auto_2", ...
// named "structure N" with colours from a fixed palette, in order of their
// first contour (slice, then contour order).
//
// Link groups: the connected components of the links between two slices; a
// group of one lower and one upper contour is a plain band, any other is a
// branch (1:N, N:1, N:M).
#include <cstdint>
#include <span>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "builder/correspondence/correspondence.h"

namespace body {

struct StructureGroups {
    std::vector<StructureInfo> infos;
    std::vector<std::vector<std::vector<uint32_t>>> members;  // structure -> slice -> contour indices
};

StructureGroups group_structures(const ContourStack& stack, CorrespondenceMethod method);

struct LinkGroup {
    std::vector<uint32_t> lower, upper;  // contour indices, sorted, without duplicates
    std::vector<ContourLink> links;      // the group's links, in input order
};

// `links` between `lower_count` lower and some upper contours. Groups come in
// a fixed order (by an internal root), the same for the same input.
std::vector<LinkGroup> group_links(std::span<const ContourLink> links, size_t lower_count, size_t upper_count);

}  // namespace body
