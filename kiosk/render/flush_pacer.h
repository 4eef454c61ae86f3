#pragma once
// Pacing of a software rasterizer (llvmpipe, softpipe): large draws are
// flushed every kFlushTriangles (draw.h) and each flush waits for the scene
// before the last one, so at most two scenes' bins are alive, whatever the
// machine's load.
//
// Contract: a fence is deleted only after a NEWER fence has been waited for.
// llvmpipe's wait returns as soon as the fence's counter is complete, which
// its rasterizer thread sets before it unlocks the fence's mutex; deleting
// the fence just waited for freed it while that thread could still unlock
// it (a 4-byte write into freed memory; Mesa's own scene recycling has the
// same race, which default_software_rasterizer_threads() in platform.h
// avoids). A newer fence complete means every rasterizer thread finished the
// older one.
// release() (with the context current) finishes the context's work first.
#include <GLES3/gl3.h>

namespace body::render {

// The three GL sync calls the pacer makes (a table, so tests can check the
// order of calls without a driver).
struct SyncCalls {
    GLsync (*fence)();       // a fence after the commands so far, flushed
    void (*wait)(GLsync);    // blocks until the fence is complete
    void (*remove)(GLsync);  // deletes the fence
    void (*finish)();        // blocks until every command so far is complete
};
const SyncCalls& gl_sync_calls();

class FlushPacer {
public:
    explicit FlushPacer(const SyncCalls& calls = gl_sync_calls()) : calls_(calls) {}
    FlushPacer(const FlushPacer&) = delete;
    FlushPacer& operator=(const FlushPacer&) = delete;
    // A new fence, flushed; then waits for the one before it and deletes
    // the one before that.
    void flush();
    // Deletes what is left, after finishing the context's work.
    void release();

private:
    const SyncCalls& calls_;
    GLsync waited_ = nullptr;   // waited for; deleted once a newer one is
    GLsync pending_ = nullptr;  // not waited for yet
};

}  // namespace body::render
