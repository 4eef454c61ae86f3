#pragma once
// The order of the vertex splits inside each batch (pm::batch_levels): the
// simplifier emits them by error, so each split's parent is anywhere among the
// vertices and its number costs log2(vertices) bits in the file. The runtime
// draws at batch boundaries only (shared/pm/draw_order.h), so inside a batch any
// order that replays to the same meshes will do: the splits go in rounds (a split
// after every earlier one of its batch that touched a face it touches), each round
// sorted by parent number, and the file codes a parent as the step from the one
// before (FORMAT.md). Every batch boundary level is the same mesh as before (the
// same splits applied, vertices renumbered); a level inside a batch gets the
// largest error of the batch's splits still to come (so errors stay
// non-increasing and each level's error still bounds it).
#include "builder/lod/simplify.h"

namespace body::lod {

// Reorders `pm`'s splits inside each batch as above, renumbering the children and
// new faces to follow.
void order_splits_in_batches(ProgressiveBuild& pm);

}  // namespace body::lod
