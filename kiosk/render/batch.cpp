// Batched drawing (see batch.h). Phases per frame: form chunks for new
// batchable models, then per chunk with members on screen: copy the vertices
// of members that changed, rebuild the element stream when its key changed,
// set the slots' uniforms, draw one range per style.
#include "kiosk/render/batch.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <iterator>
#include <span>
#include <string>

#include "kiosk/render/buffer_access.h"
#include "kiosk/render/gl_util.h"
#include "kiosk/render/renderer_state.h"

namespace body::render {
namespace {

constexpr GLuint kSlot = 5;  // mesh.vert's a_slot
constexpr int kNotBatched = -2;
// A chunk's draw order is made again when the camera turned by more than
// this (15 degrees): often enough to stay front to back under an orbit, seldom
// enough that rebuilding the stream costs nothing per frame.
constexpr float kReorderCos = 0.966f;

// The batch styles, in drawing order, and their programs.
constexpr Style kBatchStyles[] = {Style::Smooth, Style::Baseline};
int style_index(Style s) { return s == Style::Smooth ? 0 : s == Style::Baseline ? 1 : -1; }

// A batch program, linked at its first draw; a_slot has its location in the shader (kSlot).
Program batch_program(const char* frag, int slots) {
    return deferred_program("mesh.vert", frag, "#define BODY_BATCH " + std::to_string(slots) + "\n");
}

// The room a slot gets: what the model's own buffers hold now.
size_t room_of(const Model& m) { return std::max(m.vertex_count, std::min(m.vertex_allocated, m.vertex_capacity)); }

// Lays out the chunk's buffers for its members' rooms: bases, slot numbers,
// buffers (re)allocated; every member's vertices are copied again when next drawn.
void lay_out(BatchChunk& c) {
    c.vertex_total = 0;
    for (size_t i = 0; i < c.members.size(); ++i) {
        c.vertex_base[i] = c.vertex_total;
        c.vertex_room[i] = c.members[i] ? room_of(*c.members[i]) : 0;
        c.copied_version[i] = UINT64_MAX;
        c.vertex_total += c.vertex_room[i];
    }
    c.stream_key.clear();
    std::vector<uint8_t> slots(c.vertex_total);
    for (size_t i = 0; i < c.members.size(); ++i)
        std::fill_n(slots.begin() + static_cast<std::ptrdiff_t>(c.vertex_base[i]), c.vertex_room[i],
                    static_cast<uint8_t>(i));
    const auto total = static_cast<GLsizeiptr>(std::max<size_t>(c.vertex_total, 1));
    glBindBuffer(GL_ARRAY_BUFFER, c.vbo_position);
    glBufferData(GL_ARRAY_BUFFER, total * 6, nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, c.vbo_normal);
    glBufferData(GL_ARRAY_BUFFER, total * 2, nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, c.vbo_slot);
    glBufferData(GL_ARRAY_BUFFER, total, slots.empty() ? nullptr : slots.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
}

// `models` (batchable, none in a chunk yet) appended to chunk number `index`,
// `c`, as its next slots; the caller lays the chunk out.
void join(BatchChunk& c, size_t index, std::span<Model* const> models) {
    for (Model* m : models) {
        m->batch_chunk = static_cast<int>(index);
        m->batch_slot = static_cast<int>(c.members.size());
        c.members.push_back(m);
    }
    c.vertex_base.resize(c.members.size());
    c.vertex_room.resize(c.members.size());
    c.copied_version.resize(c.members.size());
}

// A chunk for `models` (batchable, none in a chunk yet), its buffers laid out
// for their rooms.
BatchChunk make_chunk(std::span<Model* const> models, std::vector<BatchChunk>& chunks) {
    BatchChunk c;
    join(c, chunks.size(), models);
    glGenVertexArrays(1, &c.vao);
    glBindVertexArray(c.vao);
    GLuint buffers[4];
    glGenBuffers(4, buffers);
    c.vbo_position = buffers[0];
    c.vbo_normal = buffers[1];
    c.vbo_slot = buffers[2];
    c.ebo = buffers[3];
    lay_out(c);
    glBindBuffer(GL_ARRAY_BUFFER, c.vbo_position);
    glVertexAttribPointer(kPosition, 3, GL_UNSIGNED_SHORT, GL_FALSE, 6, nullptr);
    glEnableVertexAttribArray(kPosition);
    glBindBuffer(GL_ARRAY_BUFFER, c.vbo_normal);
    glVertexAttribPointer(kNormalCode, 2, GL_UNSIGNED_BYTE, GL_FALSE, 2, nullptr);
    glEnableVertexAttribArray(kNormalCode);
    glBindBuffer(GL_ARRAY_BUFFER, c.vbo_slot);
    glVertexAttribPointer(kSlot, 1, GL_UNSIGNED_BYTE, GL_FALSE, 1, nullptr);
    glEnableVertexAttribArray(kSlot);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, c.ebo);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    return c;
}

// Chunks for the models of `drawn` that have none: the last chunk's free
// slots first (that chunk laid out again), then new chunks of slots_per_chunk.
// Every chunk but the last stays full, so models that arrive over several
// frames (a streamed start draws its first frame before most have) end in as
// few chunks, and draw calls, as models that came at once.
void form_chunks(Batches& b, const std::vector<Model*>& drawn) {
    std::vector<Model*> fresh;
    for (Model* m : drawn)
        if (m->batch_chunk == -1) fresh.push_back(m);
    const auto per_chunk = static_cast<size_t>(b.slots_per_chunk);
    size_t first = 0;
    if (!fresh.empty() && !b.chunks.empty() && b.chunks.back().members.size() < per_chunk) {
        BatchChunk& last = b.chunks.back();
        first = std::min(fresh.size(), per_chunk - last.members.size());
        join(last, b.chunks.size() - 1, std::span(fresh).first(first));
        lay_out(last);
    }
    for (; first < fresh.size(); first += per_chunk) {
        const size_t n = std::min(fresh.size() - first, per_chunk);
        b.chunks.push_back(make_chunk(std::span(fresh).subspan(first, n), b.chunks));
    }
}

// Copies the vertex codes of the chunk's member `slot` when the model changed
// since; a model whose format left codes leaves the chunk (false).
bool sync_vertices(BatchChunk& c, size_t slot) {
    Model& m = *c.members[slot];
    if (c.copied_version[slot] == m.geometry_version) return true;
    if (!m.quantized || !m.normal_codes) {
        m.batch_chunk = kNotBatched;
        c.members[slot] = nullptr;
        return false;
    }
    const auto base = static_cast<GLintptr>(c.vertex_base[slot]);
    const auto count = static_cast<GLsizeiptr>(m.vertex_count);
    glBindBuffer(GL_COPY_READ_BUFFER, m.vbo_position);
    glBindBuffer(GL_COPY_WRITE_BUFFER, c.vbo_position);
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, base * 6, count * 6);
    glBindBuffer(GL_COPY_READ_BUFFER, m.vbo_normal);
    glBindBuffer(GL_COPY_WRITE_BUFFER, c.vbo_normal);
    glCopyBufferSubData(GL_COPY_READ_BUFFER, GL_COPY_WRITE_BUFFER, 0, base * 2, count * 2);
    glBindBuffer(GL_COPY_READ_BUFFER, 0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    c.copied_version[slot] = m.geometry_version;
    return true;
}

// The order the chunk's `slots` are drawn in: nearest bounding-sphere centre
// first (ties by slot), so that the front structures fill the depth buffer
// before the ones they hide are shaded (a software rasterizer shades only the
// fragments that pass the early depth test); slot order is arrival order.
std::vector<size_t> draw_order(const BatchChunk& c, const std::vector<size_t>& slots, const glm::mat4& view) {
    std::vector<std::pair<float, size_t>> by_depth;
    by_depth.reserve(slots.size());
    for (size_t slot : slots) by_depth.emplace_back(view_depth(*c.members[slot], view), slot);
    std::sort(by_depth.begin(), by_depth.end());
    std::vector<size_t> order;
    order.reserve(slots.size());
    for (const auto& [depth, slot] : by_depth) order.push_back(slot);
    return order;
}

// The element stream of the chunk's `slots` (on screen this frame), by style:
// each member's index prefix (or its ordered level, level_order.h) read back
// from its element buffer, offset to the chunk's vertices, nearest member
// first. Rebuilt only when the key (slot, style, index count, geometry version
// and element buffer of each) differs from the last frame's, or the camera
// turned by more than 15 degrees (kReorderCos) since the order was made.
void build_stream(BatchChunk& c, const std::vector<size_t>& slots, const glm::mat4& view) {
    std::vector<uint64_t> key;
    key.reserve(slots.size() * 4);
    for (size_t slot : slots) {
        const Model& m = *c.members[slot];
        key.push_back(slot << 8 | static_cast<uint64_t>(m.state.style));
        key.push_back(m.index_count);
        key.push_back(m.geometry_version);
        key.push_back(drawn_element_buffer(m));
    }
    // The camera's forward axis in world space (the view's third row, negated).
    const Vec3f forward = -Vec3f(view[0][2], view[1][2], view[2][2]);
    if (key == c.stream_key && glm::dot(forward, c.order_forward) >= kReorderCos) return;
    c.stream_key = std::move(key);
    c.order_forward = forward;
    const std::vector<size_t> order = draw_order(c, slots, view);
    std::vector<uint32_t> stream;
    for (size_t k = 0; k < std::size(kBatchStyles); ++k) {
        const Style style = kBatchStyles[k];
        c.range_first[k] = stream.size();
        for (size_t slot : order) {
            const Model& m = *c.members[slot];
            if (m.state.style != style) continue;
            const MappedBuffer<uint32_t> map(m, drawn_element_buffer(m), m.index_count);
            if (map.data().size() != m.index_count) continue;  // not drawn this time (a lost mapping)
            const auto base = static_cast<uint32_t>(c.vertex_base[slot]);
            for (uint32_t i : map.data()) stream.push_back(i + base);
        }
        c.range_count[k] = stream.size() - c.range_first[k];
    }
    glBindVertexArray(c.vao);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(stream.size() * 4), stream.data(), GL_DYNAMIC_DRAW);
    glBindVertexArray(0);
    c.stream_entries = stream.size();
}

// The slots' uniforms: exactly the per-model path's values (set_matrices, draw_coloured).
void fill_slots(const BatchChunk& c, const Frame& f, const std::vector<size_t>& slots, std::vector<glm::vec4>& out) {
    out.assign(static_cast<size_t>(slots.empty() ? 0 : slots.back() + 1) * kBatchSlotVectors, glm::vec4(0.0f));
    for (size_t slot : slots) {
        const Model& m = *c.members[slot];
        const glm::mat4 mv = f.view * m.state.transform;
        const glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(mv)));
        glm::vec4* v = out.data() + slot * kBatchSlotVectors;
        for (int i = 0; i < 4; ++i) v[i] = mv[i];
        for (int i = 0; i < 3; ++i) v[4 + i] = glm::vec4(nm[i], 0.0f);
        v[7] = glm::vec4(m.pos_origin, 0.0f);
        v[8] = glm::vec4(m.pos_scale, 0.0f);
        v[9] = glm::vec4(m.state.color, 1.0f);
    }
}

void draw_chunk(RendererState& s, Frame& f, BatchChunk& c, const std::vector<size_t>& slots,
                std::vector<glm::vec4>& uniforms) {
    build_stream(c, slots, f.view);
    fill_slots(c, f, slots, uniforms);
    for (size_t k = 0; k < std::size(kBatchStyles); ++k) {
        const Style style = kBatchStyles[k];
        if (c.range_count[k] == 0) continue;
        Program& p = style == Style::Smooth ? s.batches.smooth : s.batches.baseline;
        f.use(p);
        if (p.frame_uniforms != f.serial) {
            glUniformMatrix4fv(p.loc("u_projection"), 1, GL_FALSE, glm::value_ptr(f.projection));
            glUniform4fv(p.loc("u_view_ray"), 1, glm::value_ptr(f.view_ray));
            p.frame_uniforms = f.serial;
        }
        if (style == Style::Smooth) set_lights(p, f);
        glUniform4fv(p.loc("u_slots"), static_cast<GLsizei>(uniforms.size()), glm::value_ptr(uniforms[0]));
        draw_element_range(f, c.vao, c.range_first[k], c.range_count[k]);
        ++s.stats.draw_calls;
    }
}

}  // namespace

Status init_batches(Batches& b, bool on) {
    b.enabled = false;
    const char* env = std::getenv("BODY_BATCH");
    if (!on || (env && std::strcmp(env, "0") == 0)) return ok_status();
    GLint vectors = 0;
    glGetIntegerv(GL_MAX_VERTEX_UNIFORM_VECTORS, &vectors);
    // mesh.vert's own uniforms take about 20 vectors; slot numbers are bytes.
    const int slots = std::min(255, (vectors - 32) / kBatchSlotVectors);
    if (slots < 8) return ok_status();
    b.smooth = batch_program("smooth.frag", slots);
    b.baseline = batch_program("baseline.frag", slots);
    b.slots_per_chunk = slots;
    b.enabled = true;
    return ok_status();
}

void shutdown_batches(Batches& b) {
    for (BatchChunk& c : b.chunks) {
        GLuint buffers[] = {c.vbo_position, c.vbo_normal, c.vbo_slot, c.ebo};
        glDeleteBuffers(4, buffers);
        glDeleteVertexArrays(1, &c.vao);
    }
    b.chunks.clear();
    for (Program* p : {&b.smooth, &b.baseline}) {
        if (p->id) glDeleteProgram(p->id);
        *p = Program{};
    }
    b.enabled = false;
}

bool batchable(const Frame& f, const Model& m, bool fade_rest) {
    const ModelState& st = m.state;
    return !f.clipping && !m.internal && !st.selected && !fade_rest && style_index(st.style) >= 0 &&
           m.batch_chunk != kNotBatched && m.vertex_capacity <= kMaxBatchedVertices && m.quantized && m.normal_codes &&
           !(m.vbo_morph && st.morph < 1.0f && st.morph_begin < m.vertex_count);
}

std::vector<Model*> draw_batched(RendererState& s, Frame& f, const std::vector<Model*>& drawn) {
    Batches& b = s.batches;
    form_chunks(b, drawn);
    // Chunks whose members outgrew their rooms laid out again, before any copy this frame.
    for (Model* m : drawn) {
        BatchChunk& c = b.chunks[static_cast<size_t>(m->batch_chunk)];
        if (m->vertex_count > c.vertex_room[static_cast<size_t>(m->batch_slot)]) lay_out(c);
    }
    // The slots on screen per chunk, in slot order.
    std::vector<std::vector<size_t>> on_screen(b.chunks.size());
    std::vector<Model*> left;
    for (Model* m : drawn) {
        BatchChunk& c = b.chunks[static_cast<size_t>(m->batch_chunk)];
        const auto slot = static_cast<size_t>(m->batch_slot);
        if (!sync_vertices(c, slot)) {
            left.push_back(m);
            continue;
        }
        on_screen[static_cast<size_t>(m->batch_chunk)].push_back(slot);
        ++s.stats.models_drawn;
        s.stats.triangles += m->index_count / 3;
    }
    std::vector<glm::vec4> uniforms;
    for (size_t i = 0; i < b.chunks.size(); ++i) {
        std::sort(on_screen[i].begin(), on_screen[i].end());
        if (!on_screen[i].empty()) draw_chunk(s, f, b.chunks[i], on_screen[i], uniforms);
    }
    BODY_GL_CHECK("batches");
    return left;
}

void forget_batched(RendererState& s, const Model& m) {
    if (m.batch_chunk < 0) return;
    BatchChunk& c = s.batches.chunks[static_cast<size_t>(m.batch_chunk)];
    c.members[static_cast<size_t>(m.batch_slot)] = nullptr;
    c.stream_key.clear();  // rebuilt without it
}

size_t batch_gpu_bytes(const Batches& b) {
    size_t total = 0;
    for (const BatchChunk& c : b.chunks) total += c.vertex_total * 9 + c.stream_entries * 4;
    return total;
}

}  // namespace body::render
