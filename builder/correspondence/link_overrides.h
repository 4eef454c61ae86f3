#pragma once
// The stack's "links" overrides (contour_stack.h) applied where correspondence
// is decided: structure grouping (grouping.cpp), the pipeline's bands and
// branches (pipeline/build_pipeline.cpp) and the link table (link_table.h).
// Contours are matched by their file reference (Contour::source_slice /
// source_contour), which repairs keep, so an override still names the pieces
// of a contour that validation split or cleaned.
#include <span>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "builder/correspondence/correspondence.h"

namespace body {

// Removes from `stack` the contours its links mark excluded.
void drop_excluded_contours(ContourStack& stack);

// Cuts and joins of `overrides` applied to `links` between the contours
// `lower` and `upper` (positions, as correspond_contours numbers them): a
// link between the two contours of a cut is removed; the two contours of a
// join, one among `lower` and the other among `upper`, are linked. The
// result is sorted, without duplicates.
void apply_link_overrides(std::span<const LinkOverride> overrides, std::span<const Contour* const> lower,
                          std::span<const Contour* const> upper, std::vector<ContourLink>& links);

}  // namespace body
