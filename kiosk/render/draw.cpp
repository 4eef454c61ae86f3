// Uniforms and draw calls shared by the styles (see draw.h).
#include "kiosk/render/draw.h"

#include <algorithm>
#include <cstdint>
#include <glm/gtc/type_ptr.hpp>

namespace body::render {

void set_matrices(Program& p, const Frame& f, const Model& m) {
    glm::mat4 mv = f.view * m.state.transform;
    glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(mv)));
    if (p.frame_uniforms != f.serial) {
        glUniformMatrix4fv(p.loc("u_projection"), 1, GL_FALSE, glm::value_ptr(f.projection));
        glUniform4fv(p.loc("u_view_ray"), 1, glm::value_ptr(f.view_ray));
        p.frame_uniforms = f.serial;
    }
    glUniformMatrix4fv(p.loc("u_model_view"), 1, GL_FALSE, glm::value_ptr(mv));
    glUniformMatrix3fv(p.loc("u_normal_matrix"), 1, GL_FALSE, glm::value_ptr(nm));
    glUniform3fv(p.loc("u_pos_origin"), 1, glm::value_ptr(m.pos_origin));
    glUniform3fv(p.loc("u_pos_scale"), 1, glm::value_ptr(m.pos_scale));
    glUniform1i(p.loc("u_normal_codes"), m.normal_codes ? 1 : 0);
    const bool morphing = m.vbo_morph && m.state.morph < 1.0f && m.state.morph_begin < m.vertex_count;
    glUniform1f(p.loc("u_morph"), morphing ? std::max(m.state.morph, 0.0f) : 1.0f);
    glUniform1i(p.loc("u_morph_begin"), morphing ? static_cast<GLint>(m.state.morph_begin) : INT32_MAX);
}

void set_lights(Program& p, const Frame& f) {
    if (p.frame_lights == f.serial) return;
    p.frame_lights = f.serial;
    const Lighting& l = *f.lighting;
    auto unit = [](Vec3f v) { return glm::length(v) > 0.0f ? glm::normalize(v) : Vec3f(0.0f, 0.0f, 1.0f); };
    const Vec3f key = unit(l.key_dir), fill = unit(l.fill_dir), rim = unit(l.rim_dir);
    glUniform3fv(p.loc("u_key_dir"), 1, glm::value_ptr(key));
    glUniform3fv(p.loc("u_fill_dir"), 1, glm::value_ptr(fill));
    glUniform3fv(p.loc("u_rim_dir"), 1, glm::value_ptr(rim));
    glUniform4f(p.loc("u_light_levels"), l.key, l.fill, l.rim, l.ambient);
    glUniform3fv(p.loc("u_half_dir"), 1, glm::value_ptr(unit(key + Vec3f(0.0f, 0.0f, 1.0f))));
    glUniform3fv(p.loc("u_key_light"), 1, glm::value_ptr(key * l.key));
    glUniform3fv(p.loc("u_fill_light"), 1, glm::value_ptr(fill * l.fill));
    glUniform2f(p.loc("u_spec_rim"), 0.25f * l.key, 0.5f * l.rim);
}

void draw_coloured(Frame& f, Program& p, const Model& m, const Vec3f& color, bool lit) {
    f.use(p);
    set_matrices(p, f, m);
    if (lit) set_lights(p, f);
    glUniform4f(p.loc("u_color"), color.r, color.g, color.b, 1.0f);
    draw_triangles(f, m);
}

void draw_triangles(const Frame& f, const Model& m) {
    const GLuint ebo = drawn_element_buffer(m);
    if (ebo == m.ebo) {
        draw_element_range(f, m.vao, 0, m.index_count);
        return;
    }
    // The ordered level for this draw; the vertex array keeps the prefix.
    glBindVertexArray(m.vao);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
    draw_element_range(f, m.vao, 0, m.index_count);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ebo);
}

void draw_element_range(const Frame& f, GLuint vao, size_t first, size_t count) {
    glBindVertexArray(vao);
    const size_t chunk = 3 * kFlushTriangles;
    if (!f.flush_large_draws || count <= chunk) {
        glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(count), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(first * sizeof(uint32_t)));
        return;
    }
    for (size_t done = 0; done < count; done += chunk) {
        glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(std::min(chunk, count - done)), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>((first + done) * sizeof(uint32_t)));
        f.pacer->flush();
    }
}

}  // namespace body::render
