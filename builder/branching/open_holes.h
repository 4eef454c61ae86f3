#pragma once
// Open holes: a 1:1 pair where a hole on one slice opens into a notch of the
// other slice's contour. The notched contour is split between the solid
// contour and its open holes (partition_bands.h, chords between the slices),
// so the notch's walls run down to the hole instead of a band sweeping across
// the solid.
#include <cstdint>

#include "builder/branching/structure_surface.h"

namespace body {

// For the solid loops `lower` (slice s) and `upper` (slice s+1), linked 1:1.
// `hole_links` are the slice pair's hole links (loop indices, as built). A hole
// opens when none of them continues it towards the other slice and a quarter or
// more of its vertices lie outside the other contour. Chords go at their
// blended heights (chord_heights.h), else only where those dip below
// mid-slice, else level at mid-slice or as close to it as they can towards the
// notched contour without the construction crossing itself. Returns true when built (the open holes are
// then linked); false, with nothing built, when no hole opens or every try
// crosses itself.
Result<bool> connect_open_holes(StructureSurface& surface, size_t s, uint32_t lower, uint32_t upper,
                                std::span<const ContourLink> hole_links);

}  // namespace body
