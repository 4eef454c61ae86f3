// Normals as a .bpm keeps them: 8:8 octahedral codes uploaded as they are (2
// bytes a vertex, MeshData::normal_codes) and decoded in mesh.vert. The
// shader's decode is checked against pm::oct_decode8 for every one of the
// 65536 codes (captured with transform feedback), and a model drawn from codes
// against the same model drawn from the decoded floats (the 2_10_10_10 path),
// also after update_model patched float normals into a model of codes.
#include <GLES3/gl3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "shared/pm/quantize.h"
#include "tests/render/render_fixture.h"

namespace body::render {
namespace {

using test::RenderFixture;

#define REQUIRE_GL(f) \
    if (!(f).ok()) GTEST_SKIP() << "no headless EGL: " << (f).why()

// The .bpm writer's 8:8 octahedral code of a unit vector.
void encode(const Vec3f& n, uint8_t out[2]) { pm::oct_encode8(n.x, n.y, n.z, out); }

GLuint compile(GLenum type, const char* src) {
    const GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = {};
        glGetShaderInfoLog(s, sizeof(log), nullptr, log);
        ADD_FAILURE() << "compile: " << log;
    }
    return s;
}

TEST(RenderNormalCodes, ShaderDecodeMatchesTheCpuDecodeForEveryCode) {
    RenderFixture f(16, 16);
    REQUIRE_GL(f);
    const char* vs = shader_source("mesh.vert");
    ASSERT_NE(vs, nullptr);
    const char* fs =
        "#version 300 es\nprecision mediump float;\nin vec3 v_view_normal;\nout vec4 o;\n"
        "void main() { o = vec4(v_view_normal, 1.0); }\n";
    const GLuint program = glCreateProgram();
    const GLuint v = compile(GL_VERTEX_SHADER, vs), fr = compile(GL_FRAGMENT_SHADER, fs);
    glAttachShader(program, v);
    glAttachShader(program, fr);
    const char* varyings[] = {"v_view_normal"};
    glTransformFeedbackVaryings(program, 1, varyings, GL_INTERLEAVED_ATTRIBS);
    glLinkProgram(program);
    glDeleteShader(v);
    glDeleteShader(fr);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    ASSERT_TRUE(linked);
    glUseProgram(program);
    const glm::mat4 identity(1.0f);
    const glm::mat3 identity3(1.0f);
    glUniformMatrix4fv(glGetUniformLocation(program, "u_model_view"), 1, GL_FALSE, &identity[0][0]);
    glUniformMatrix4fv(glGetUniformLocation(program, "u_projection"), 1, GL_FALSE, &identity[0][0]);
    glUniformMatrix3fv(glGetUniformLocation(program, "u_normal_matrix"), 1, GL_FALSE, &identity3[0][0]);
    glUniform3f(glGetUniformLocation(program, "u_pos_scale"), 1.0f, 1.0f, 1.0f);
    glUniform1f(glGetUniformLocation(program, "u_morph"), 1.0f);
    glUniform1i(glGetUniformLocation(program, "u_morph_begin"), 1 << 30);
    glUniform1i(glGetUniformLocation(program, "u_normal_codes"), 1);

    constexpr size_t kCodes = 65536;
    std::vector<uint8_t> codes(kCodes * 2);
    for (size_t c = 0; c < kCodes; ++c) {
        codes[c * 2] = static_cast<uint8_t>(c & 0xff);
        codes[c * 2 + 1] = static_cast<uint8_t>(c >> 8);
    }
    GLuint vao = 0, buffers[2] = {};
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glGenBuffers(2, buffers);
    glBindBuffer(GL_ARRAY_BUFFER, buffers[0]);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(codes.size()), codes.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(4, 2, GL_UNSIGNED_BYTE, GL_FALSE, 2, nullptr);  // a_normal_code
    glEnableVertexAttribArray(4);
    glBindBuffer(GL_TRANSFORM_FEEDBACK_BUFFER, buffers[1]);
    glBufferData(GL_TRANSFORM_FEEDBACK_BUFFER, static_cast<GLsizeiptr>(kCodes * 12), nullptr, GL_STATIC_READ);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, buffers[1]);
    glEnable(GL_RASTERIZER_DISCARD);
    glBeginTransformFeedback(GL_POINTS);
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(kCodes));
    glEndTransformFeedback();
    glDisable(GL_RASTERIZER_DISCARD);
    const auto* out = static_cast<const float*>(
        glMapBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, static_cast<GLsizeiptr>(kCodes * 12), GL_MAP_READ_BIT));
    ASSERT_NE(out, nullptr);
    float worst = 0.0f;
    size_t worst_code = 0;
    for (size_t c = 0; c < kCodes; ++c) {
        float n[3];
        pm::oct_decode8(&codes[c * 2], n);
        for (int k = 0; k < 3; ++k) {
            const float d = std::abs(out[c * 3 + static_cast<size_t>(k)] - n[k]);
            if (d > worst) worst = d, worst_code = c;
        }
    }
    glUnmapBuffer(GL_TRANSFORM_FEEDBACK_BUFFER);
    EXPECT_LT(worst, 1e-5f) << "code " << worst_code;
    glDeleteBuffers(2, buffers);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(program);
}

TEST(RenderNormalCodes, CodesDrawLikeTheirDecodedFloats) {
    RenderFixture f(240, 240);
    REQUIRE_GL(f);
    const test::GenMesh sphere = test::icosphere(3);
    // Normals tilted off the radial direction so that a wrong decode shows.
    std::vector<uint8_t> codes(sphere.positions.size() * 2), flipped(codes.size());
    std::vector<Vec3f> decoded(sphere.positions.size());
    for (size_t v = 0; v < sphere.positions.size(); ++v) {
        const Vec3f p = sphere.positions[v];
        encode(glm::normalize(p + Vec3f(0.3f * std::sin(7.0f * p.y), 0.0f, 0.2f)), &codes[v * 2]);
        encode(-glm::normalize(p), &flipped[v * 2]);
        float n[3];
        pm::oct_decode8(&codes[v * 2], n);
        decoded[v] = Vec3f(n[0], n[1], n[2]);
    }
    const View cam = View::framing(Vec3f(0.0f), 1.05f, Vec3f(0.3f, 0.5f, 1.0f));
    auto draw_one = [&](const MeshData& mesh) {
        auto id = f.renderer().add_model(mesh, "sphere");
        EXPECT_TRUE(id.ok());
        f.renderer().state(id.value())->style = Style::Smooth;
        const Image img = f.draw(cam);
        return std::pair{id.value(), img};
    };
    MeshData from_codes{sphere.positions, {}, sphere.indices};
    from_codes.normal_codes = codes;
    auto [coded_id, coded] = draw_one(from_codes);
    f.renderer().remove_model(coded_id);
    auto [float_id, floats] = draw_one(MeshData{sphere.positions, decoded, sphere.indices});
    f.renderer().remove_model(float_id);
    const test::ImageDiff same = test::compare(floats, coded, 8);
    EXPECT_LT(same.bad_block_fraction, 0.002);
    EXPECT_NEAR(same.mean_luma_delta, 0.0, 0.5);

    // Flipped normals light the sphere differently: the comparison can fail.
    MeshData from_flipped{sphere.positions, {}, sphere.indices};
    from_flipped.normal_codes = flipped;
    auto [flipped_id, flipped_image] = draw_one(from_flipped);
    EXPECT_GT(test::compare(coded, flipped_image, 8).bad_block_fraction, 0.2);

    // Float normals patched into a model of codes (encoded as they go up) draw
    // like the codes they came from.
    MeshData patch{sphere.positions, decoded, sphere.indices};
    ASSERT_TRUE(f.renderer().update_model(flipped_id, patch, Dirty{0, sphere.positions.size(), 0, 0}).ok());
    const test::ImageDiff patched = test::compare(coded, f.draw(cam), 8);
    EXPECT_LT(patched.bad_block_fraction, 0.002);
}

}  // namespace
}  // namespace body::render
