// The grey-level volume on the cut plane's caps (contract in cut_volume.h).
#include "kiosk/render/cut_volume.h"

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "kiosk/render/draw.h"
#include "kiosk/render/renderer_state.h"
#include "shared/scene/slice_volume.h"

namespace body::render {

Program* use_cut_volume(CutVolumeState& volume, Frame& f) {
    if (!volume.texture || !(f.options->cut.volume_mix > 0.0f)) return nullptr;
    Program& p = volume.program;
    f.use(p);
    const glm::mat4 view_to_texture = volume.world_to_texture * glm::inverse(f.view);
    glUniformMatrix4fv(p.loc("u_view_to_volume"), 1, GL_FALSE, glm::value_ptr(view_to_texture));
    glUniform1f(p.loc("u_volume_mix"), std::min(f.options->cut.volume_mix, 1.0f));
    glUniform1i(p.loc("u_volume"), 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_3D, volume.texture);
    return &p;
}

void free_cut_volume(CutVolumeState& volume) {
    if (volume.texture) glDeleteTextures(1, &volume.texture);
    if (volume.program.id) glDeleteProgram(volume.program.id);
    if (volume.plane_program.id) glDeleteProgram(volume.plane_program.id);
    volume = CutVolumeState{};
}

Status Renderer::set_cut_volume(const SliceVolume* source) {
    CutVolumeState& volume = s_->cut_volume;
    free_cut_volume(volume);
    if (!source) return ok_status();
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max_size);
    for (uint32_t d : source->dims)
        if (d > static_cast<uint32_t>(max_size))
            return runtime_error("grey-level volume: dimension " + std::to_string(d) + " over the GPU's " +
                                 std::to_string(max_size));
    auto program = link_shader_pair("cap.vert", "cap_volume.frag");
    if (!program) return program.error();
    volume.program = std::move(program.value());
    auto plane_program = link_shader_pair("cap.vert", "volume_plane.frag");
    if (!plane_program) {
        free_cut_volume(volume);
        return plane_program.error();
    }
    volume.plane_program = std::move(plane_program.value());
    // Voxel index -> world is the file's affine; texture coordinates are (index + 0.5) / dims.
    glm::mat4 to_world(1.0f);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) to_world[c][r] = source->affine[size_t(r * 4 + c)];
    const Vec3f dims(static_cast<float>(source->dims[0]), static_cast<float>(source->dims[1]),
                     static_cast<float>(source->dims[2]));
    // The box spans voxel indices -0.5 .. dims - 0.5 (texture 0 .. 1).
    volume.world_center = Vec3f(to_world * glm::vec4(0.5f * dims - 0.5f, 1.0f));
    volume.world_radius = glm::length(glm::mat3(to_world) * (0.5f * dims));
    volume.world_to_texture = glm::scale(glm::mat4(1.0f), 1.0f / dims) * glm::translate(glm::mat4(1.0f), Vec3f(0.5f)) *
                              glm::inverse(to_world);
    while (glGetError() != GL_NO_ERROR) {
    }  // earlier errors are not this upload's
    glGenTextures(1, &volume.texture);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_3D, volume.texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage3D(GL_TEXTURE_3D, 0, GL_R8, static_cast<GLsizei>(source->dims[0]), static_cast<GLsizei>(source->dims[1]),
                 static_cast<GLsizei>(source->dims[2]), 0, GL_RED, GL_UNSIGNED_BYTE, source->voxels.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_3D, 0);
    volume.bytes = source->voxels.size();
    if (glGetError() != GL_NO_ERROR) {
        free_cut_volume(volume);
        return runtime_error("grey-level volume: the GPU refused the 3-D texture");
    }
    return ok_status();
}

}  // namespace body::render
