#pragma once
// Procedural tonal art map (Praun, Hoppe, Webb, Finkelstein 2001, "Real-time
// hatching"): `tones` nested hatch textures from light to dark, each with its
// own mip chain drawn at that resolution so that stroke width stays one texel
// and tone is matched per level. Tone k contains every stroke of tone k-1
// (nesting); tones past the middle add cross-hatching. Deterministic (fixed
// seed), so the same bytes on every machine.
#include <cstdint>
#include <vector>

namespace body::render {

struct TonalArtMap {
    int size = 0;   // level 0 is size x size
    int tones = 0;  // layers, lightest first
    // levels[level][tone] holds (size>>level)^2 bytes, 255 = paper, 0 = ink.
    std::vector<std::vector<std::vector<uint8_t>>> levels;
    // Mean darkness (0 paper .. 1 ink) of a tone at level 0.
    double darkness(int tone) const;
};

// size: a power of two >= 8.
TonalArtMap make_tonal_art_map(int size = 256, int tones = 6);

}  // namespace body::render
