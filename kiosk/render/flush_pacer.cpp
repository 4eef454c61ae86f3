// Fence pacing of software rasterizers (see flush_pacer.h).
#include "kiosk/render/flush_pacer.h"

namespace body::render {

const SyncCalls& gl_sync_calls() {
    static const SyncCalls calls{
        [] {
            GLsync f = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
            glFlush();
            return f;
        },
        [](GLsync f) { glClientWaitSync(f, 0, GL_TIMEOUT_IGNORED); },
        [](GLsync f) { glDeleteSync(f); },
        [] { glFinish(); },
    };
    return calls;
}

void FlushPacer::flush() {
    GLsync fence = calls_.fence();
    if (pending_) {
        calls_.wait(pending_);
        if (waited_) calls_.remove(waited_);
        waited_ = pending_;
    }
    pending_ = fence;
}

void FlushPacer::release() {
    if (!waited_ && !pending_) return;
    calls_.finish();
    if (waited_) calls_.remove(waited_);
    if (pending_) calls_.remove(pending_);
    waited_ = pending_ = nullptr;
}

}  // namespace body::render
