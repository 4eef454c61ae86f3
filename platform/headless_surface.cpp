// Headless backend: EGL on the Mesa surfaceless platform (no display server, no
// DRM master) with an offscreen RGBA8 + depth framebuffer; falls back to the
// first EGL device (drivers without that platform), then to the default display
// with a small pbuffer. Used for screenshots, tests, benchmarks.
#include <GLES3/gl3.h>

#include <chrono>

#include "platform/egl_context.h"
#include "platform/platform.h"
#include "platform/quit_signal.h"

namespace body::platform {
namespace {

class HeadlessSurface final : public Surface {
public:
    ~HeadlessSurface() override {
        remove_quit_handlers();
        if (egl_) {
            (void)egl_->make_current();
            if (fbo_) glDeleteFramebuffers(1, &fbo_);
            GLuint rbs[2] = {color_, depth_};
            glDeleteRenderbuffers(2, rbs);
        }
    }
    Status init(const SurfaceOptions& options) {
        install_quit_handlers();  // SIGTERM ends a headless kiosk or soak by the loop's own exit
        width_ = options.width > 0 ? options.width : 1280;
        height_ = options.height > 0 ? options.height : 800;
        auto egl = EglContext::open(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, 0, 0);
        if (!egl) egl = EglContext::open_first_device();
        if (!egl) {
            egl = EglContext::open(0, EGL_DEFAULT_DISPLAY, EGL_PBUFFER_BIT, 0);
            if (!egl) return runtime_error("headless: " + egl.error().message);
            egl_ = std::move(egl.value());
            if (auto s = egl_->create_pbuffer_surface(16, 16); !s) return s;
        } else {
            egl_ = std::move(egl.value());
        }
        if (auto s = egl_->make_current(); !s) return s;
        GLint max_rb = 0;
        glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
        if (width_ > max_rb || height_ > max_rb)
            return input_error("headless: size " + std::to_string(width_) + "x" + std::to_string(height_) +
                               " exceeds the renderbuffer limit " + std::to_string(max_rb));
        glGenRenderbuffers(1, &color_);
        glBindRenderbuffer(GL_RENDERBUFFER, color_);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width_, height_);
        glGenRenderbuffers(1, &depth_);
        glBindRenderbuffer(GL_RENDERBUFFER, depth_);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width_, height_);
        glGenFramebuffers(1, &fbo_);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return runtime_error("headless: offscreen framebuffer incomplete");
        start_ = std::chrono::steady_clock::now();
        return ok_status();
    }

    Backend backend() const override { return Backend::Headless; }
    void make_current() override { (void)egl_->make_current(); }
    Status present() override {
        glFinish();
        return ok_status();
    }
    int width() const override { return width_; }
    int height() const override { return height_; }
    unsigned framebuffer() const override { return fbo_; }
    bool poll_events(std::vector<InputEvent>&) override { return !quit_requested(); }
    double time() const override {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }

private:
    std::unique_ptr<EglContext> egl_;
    int width_ = 0, height_ = 0;
    GLuint fbo_ = 0, color_ = 0, depth_ = 0;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace

Result<std::unique_ptr<Surface>> create_headless_surface(const SurfaceOptions& options) {
    default_software_rasterizer_threads();
    return init_surface<HeadlessSurface>(options);
}

}  // namespace body::platform
