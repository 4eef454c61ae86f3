#pragma once
// The renderer's one private state struct (Dear ImGui backend shape): the
// program table, the shared vertex arrays of the line styles, the tonal art
// map, the models and the frame's statistics.
#include <GLES3/gl3.h>

#include <map>

#include "kiosk/render/batch.h"
#include "kiosk/render/buffer_access.h"
#include "kiosk/render/cut_volume.h"
#include "kiosk/render/flush_pacer.h"
#include "kiosk/render/level_order.h"
#include "kiosk/render/model.h"
#include "kiosk/render/programs.h"
#include "kiosk/render/renderer.h"
#include "kiosk/render/styles/cut_cap.h"

namespace body::render {

struct RendererState {
    bool ready = false;
    Programs programs;
    GLuint tam = 0;       // tonal art map: a 2D array texture, made at the first hatching draw (styles/hatching.cpp)
    GLuint wire_vao = 0;  // `wireframe`: a model's index buffer as the kWireVertex attribute
    // `wireframe` reads quantized positions from the position buffer through a
    // buffer texture of at most this many texels (0: not offered; styles/wireframe.cpp).
    size_t wire_buffer_texels = 0;
    GLuint quad_vao = 0, quad_ebo = 0;  // `lines`: the shared edge-quad index buffer
    std::map<ModelId, Model> models;
    ModelId next_id = 1;
    ModelId sphere = 0;
    FrameStats stats;
    uint64_t frame_serial = 0;   // frames begun (Frame::serial)
    bool trim_deferred = false;  // the first frame's heap trim, done at the end of the next frame
    Transfers transfers;
    // Software rasterizers (GL_RENDERER llvmpipe, softpipe): large draws are
    // split and flushed (draw.h, kFlushTriangles).
    bool flush_large_draws = false;
    FlushPacer pacer;           // their fences, kept across draws and frames (flush_pacer.h)
    CutCapState cut;            // the cut plane's programs (styles/cut_cap.h)
    Batches batches;            // many opaque models per draw call (batch.h)
    CutVolumeState cut_volume;  // the caps' grey-level volume (cut_volume.h)
    // Settled levels ordered off this thread (level_order.h), once they stayed
    // RendererOptions::settle_seconds.
    LevelOrderWorker level_orders;
    double settle_seconds = 0.0;
};

}  // namespace body::render
