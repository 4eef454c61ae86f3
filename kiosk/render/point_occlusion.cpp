// PointOcclusion (point_occlusion.h): one pixel per point, one occlusion query
// per pixel, against the depth buffer the frame left.
#include "kiosk/render/point_occlusion.h"

#include <GLES3/gl3.h>

#include "kiosk/render/gl_util.h"

namespace body::render {
namespace {

// The points arrive in clip space (the nudge is applied on the CPU).
constexpr const char* kVertex = R"(#version 300 es
layout(location = 0) in vec4 a_clip;
void main() {
    gl_Position = a_clip;
    gl_PointSize = 1.0;
}
)";
constexpr const char* kFragment = R"(#version 300 es
precision mediump float;
out vec4 o_color;
void main() { o_color = vec4(0.0); }
)";

}  // namespace

PointOcclusion::~PointOcclusion() = default;

Status PointOcclusion::init() {
    if (program_) return ok_status();
    auto program = link_program(kVertex, kFragment, "point_occlusion");
    if (!program) return program.error();
    program_ = program.value();
    glGenVertexArrays(1, &vao_);
    glGenBuffers(1, &vbo_);
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    BODY_GL_CHECK("point_occlusion init");
    return ok_status();
}

void PointOcclusion::shutdown() {
    if (!queries_.empty()) glDeleteQueries(static_cast<GLsizei>(queries_.size()), queries_.data());
    if (vbo_) glDeleteBuffers(1, &vbo_);
    if (vao_) glDeleteVertexArrays(1, &vao_);
    if (program_) glDeleteProgram(program_);
    queries_.clear();
    program_ = vao_ = vbo_ = 0;
    in_flight_ = 0;
}

bool PointOcclusion::test(const View& camera, const FrameOptions& frame, std::span<const Vec3f> points) {
    if (!program_ || in_flight_ > 0 || points.empty() || frame.width <= 0 || frame.height <= 0) return false;
    const glm::mat4 pv =
        camera.projection(static_cast<float>(frame.width) / static_cast<float>(frame.height)) * camera.view();
    clip_.resize(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
        const glm::vec3 p = points[i] + (camera.eye - points[i]) * kNudge;
        clip_[i] = pv * glm::vec4(p, 1.0f);
    }
    if (queries_.size() < points.size()) {
        const size_t had = queries_.size();
        queries_.resize(points.size());
        glGenQueries(static_cast<GLsizei>(points.size() - had), queries_.data() + had);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, frame.framebuffer);
    glViewport(0, 0, frame.width, frame.height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDisable(GL_BLEND);
    glDisable(GL_STENCIL_TEST);
    glUseProgram(program_);
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(clip_.size() * sizeof(glm::vec4)), clip_.data(),
                 GL_STREAM_DRAW);
    for (size_t i = 0; i < points.size(); ++i) {
        glBeginQuery(GL_ANY_SAMPLES_PASSED, queries_[i]);
        glDrawArrays(GL_POINTS, static_cast<GLint>(i), 1);
        glEndQuery(GL_ANY_SAMPLES_PASSED);
    }
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glUseProgram(0);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LEQUAL);
    BODY_GL_CHECK("point_occlusion test");
    in_flight_ = points.size();
    return true;
}

bool PointOcclusion::collect(bool wait, std::vector<char>& hidden) {
    if (in_flight_ == 0) return false;
    if (!wait) {
        for (size_t i = 0; i < in_flight_; ++i) {
            GLuint ready = GL_FALSE;
            glGetQueryObjectuiv(queries_[i], GL_QUERY_RESULT_AVAILABLE, &ready);
            if (!ready) return false;
        }
    }
    hidden.assign(in_flight_, 0);
    for (size_t i = 0; i < in_flight_; ++i) {
        GLuint passed = GL_FALSE;
        glGetQueryObjectuiv(queries_[i], GL_QUERY_RESULT, &passed);
        hidden[i] = passed ? 0 : 1;
    }
    in_flight_ = 0;
    BODY_GL_CHECK("point_occlusion collect");
    return true;
}

}  // namespace body::render
