#pragma once
// The bundle's grey-level volume on the cut plane's caps (scene.json
// cut_plane.volume, shared/scene/slice_volume.h): Renderer::set_cut_volume
// uploads it as one R8 3-D texture (linear filtering, edges clamped) and links
// cap.vert + cap_volume.frag; while it is set and CutPlane::volume_mix > 0,
// every cap pixel inside the volume mixes the cap colour with the grey level
// at that pixel's world position (the volume's affine inverted once, on the
// CPU, and joined with the inverse view each frame). Without a volume the caps
// draw exactly as before (cut_cap.cpp's plain program). CutPlane::volume_around
// shows the image around the caps as well (draw_volume_plane).
#include <GLES3/gl3.h>

#include "kiosk/render/programs.h"
#include "shared/geometry.h"

namespace body::render {

struct Frame;
struct RendererState;

struct CutVolumeState {
    GLuint texture = 0;
    Program program;        // cap.vert + cap_volume.frag
    Program plane_program;  // cap.vert + volume_plane.frag (volume_plane.cpp)
    glm::mat4 world_to_texture{1.0f};
    Vec3f world_center{0.0f};  // the volume's box: centre and half diagonal, world units
    float world_radius = 0.0f;
    size_t bytes = 0;
};

// The program to fill caps with this frame: `volume`'s (its uniforms set, the
// texture bound to unit 0) when a volume is set and the frame mixes it in,
// else nullptr.
Program* use_cut_volume(CutVolumeState& volume, Frame& f);
void free_cut_volume(CutVolumeState& volume);
// With CutPlane::volume_around, the plane's part inside the volume's box in
// the volume's grey levels, depth-tested and offset behind the caps (which lie
// on the same plane); drawn after the opaque models, before the transparent.
void draw_volume_plane(RendererState& s, Frame& f);

}  // namespace body::render
