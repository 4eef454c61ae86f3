// The grey-level volume around the cut plane's caps (contract in
// cut_volume.h, draw_volume_plane): a square of the plane covering the
// volume's bounding sphere, drawn by cap.vert, its pixels outside the volume's
// box discarded by volume_plane.frag.
#include <cmath>
#include <glm/gtc/type_ptr.hpp>

#include "kiosk/render/cut_volume.h"
#include "kiosk/render/draw.h"
#include "kiosk/render/renderer_state.h"

namespace body::render {

void draw_volume_plane(RendererState& s, Frame& f) {
    CutVolumeState& volume = s.cut_volume;
    const CutPlane& cut = f.options->cut;
    if (!volume.texture || !cut.volume_around || !volume.plane_program.id) return;
    const float len = glm::length(Vec3f(cut.plane));
    if (!(len > 0.0f)) return;
    const Vec3f n = Vec3f(cut.plane) / len;
    const float w = cut.plane.w / len;
    const float d = glm::dot(n, volume.world_center) + w;  // the box's centre from the plane
    if (std::abs(d) >= volume.world_radius) return;        // the plane misses the volume
    const float half = std::sqrt(volume.world_radius * volume.world_radius - d * d) * 1.01f;
    const Vec3f helper = std::abs(n.x) < 0.9f ? Vec3f(1.0f, 0.0f, 0.0f) : Vec3f(0.0f, 1.0f, 0.0f);
    const Vec3f u = glm::normalize(glm::cross(n, helper)), v = glm::cross(n, u);
    const glm::mat3 rot(f.view);
    const Vec3f center_view(f.view * glm::vec4(volume.world_center - n * d, 1.0f));
    const Vec3f axis_u = rot * (u * half), axis_v = rot * (v * half);

    Program& p = volume.plane_program;
    f.use(p);
    const glm::mat4 view_to_texture = volume.world_to_texture * glm::inverse(f.view);
    glUniformMatrix4fv(p.loc("u_projection"), 1, GL_FALSE, glm::value_ptr(f.projection));
    glUniformMatrix4fv(p.loc("u_view_to_volume"), 1, GL_FALSE, glm::value_ptr(view_to_texture));
    glUniform3fv(p.loc("u_center"), 1, glm::value_ptr(center_view));
    glUniform3fv(p.loc("u_axis_u"), 1, glm::value_ptr(axis_u));
    glUniform3fv(p.loc("u_axis_v"), 1, glm::value_ptr(axis_v));
    glUniform1i(p.loc("u_volume"), 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_3D, volume.texture);
    // The caps lie on this plane: pushed back a little, they win the depth test.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.0f, 4.0f);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(s.cut.cap_vao);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glEnable(GL_CULL_FACE);
    glDisable(GL_POLYGON_OFFSET_FILL);
    ++s.stats.draw_calls;
    s.stats.triangles += 2;
}

}  // namespace body::render
