#pragma once
// Readable titles from structure names as atlases and segmentations spell them:
//   "Frontal_Sup_Orb_L"          -> "Frontal sup orb", side left
//   "Left-Hippocampus"           -> "Hippocampus", side left  (FreeSurfer)
//   "ctx-rh-insula", "lh.insula" -> "Insula", side right/left
//   "Pontine_crossing_tract_(a_part_of_MCP)" -> "Pontine crossing tract (a part of MCP)"
// Side markers recognised: a suffix _L/_R/.L/.R/-L/-R/" L"/" R" or _left/_right,
// a prefix Left-/Right-/Left_/Right_/"Left "/"Right ", lh./rh., ctx-lh-/ctx-rh-.
// Underscores (and hyphens in names without spaces) become spaces, runs of
// spaces collapse, and the first letter is capitalised; other letters keep their
// case so abbreviations (MCP, CA1) survive.
#include <string>

namespace body::exhibit {

struct ReadableName {
    std::string title;  // without the side
    std::string side;   // "left", "right" or empty
    // "Title (left)" or just the title.
    std::string with_side() const { return side.empty() ? title : title + " (" + side + ")"; }
};

ReadableName readable_name(const std::string& name);

}  // namespace body::exhibit
