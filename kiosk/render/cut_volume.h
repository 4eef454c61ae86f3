#pragma once
// The bundle's grey-level volume on the cut plane's caps (scene.json
// cut_plane.volume, shared/scene/slice_volume.h): Renderer::set_cut_volume
// uploads it as one R8 3-D texture (linear filtering, edges clamped) and links
// cap.vert + cap_volume.frag; while it is set and CutPlane::volume_mix > 0,
// every cap pixel inside the volume mixes the cap colour with the grey level
// at that pixel's world position (the volume's affine inverted once, on the
// CPU, and joined with the inverse view each frame). Without a volume the caps
// draw exactly as before (cut_cap.cpp's plain program).
#include <GLES3/gl3.h>

#include "kiosk/render/programs.h"
#include "shared/geometry.h"

namespace body::render {

struct Frame;

struct CutVolumeState {
    GLuint texture = 0;
    Program program;  // cap.vert + cap_volume.frag
    glm::mat4 world_to_texture{1.0f};
    size_t bytes = 0;
};

// The program to fill caps with this frame: `volume`'s (its uniforms set, the
// texture bound to unit 0) when a volume is set and the frame mixes it in,
// else nullptr.
Program* use_cut_volume(CutVolumeState& volume, Frame& f);
void free_cut_volume(CutVolumeState& volume);

}  // namespace body::render
