// The fake KMS device (contract in drm_fake.h).
#include "drm_fake.h"

#include <cerrno>
#include <cstring>

namespace body::platform::fake {

Kms g_kms;

namespace {

constexpr uint32_t kCrtc = 41, kPlane = 31;
// Property ids: the index of (object, name) in this table, plus 1000.
std::vector<std::pair<uint32_t, std::string>> g_props;
bool g_atomic_cap = false;

std::string size(const drmModeModeInfo& m) { return std::to_string(m.hdisplay) + "x" + std::to_string(m.vdisplay); }

int fail(int error) {
    errno = error;
    return -1;
}

drmModeCrtc* get_crtc(int, uint32_t) {
    auto* c = new drmModeCrtc{};
    c->crtc_id = kCrtc;
    c->buffer_id = g_kms.screen.fb;
    c->mode_valid = g_kms.screen.on;
    c->mode = g_kms.screen.mode;
    return c;
}
void free_crtc(drmModeCrtc* c) { delete c; }

int set_crtc(int, uint32_t, uint32_t fb, uint32_t, uint32_t, uint32_t*, int, drmModeModeInfo* m) {
    if (!g_kms.master) return fail(EACCES);
    if (!g_kms.events.empty()) return fail(EBUSY);
    g_kms.commits.push_back(m ? "legacy-mode " + size(*m) + " fb " + std::to_string(fb) : "legacy-off");
    g_kms.screen = m ? Screen{fb, true, *m} : Screen{};
    return 0;
}

int wait_readable(int, int) {
    if (g_kms.hold_events > 0) {
        --g_kms.hold_events;
        return 0;
    }
    return g_kms.events.empty() ? 0 : 1;
}

int handle_event(int fd, drmEventContext* context) {
    std::vector<void*> events;
    events.swap(g_kms.events);
    for (void* data : events) context->page_flip_handler(fd, 0, 0, 0, data);
    return 0;
}

int set_client_cap(int, uint64_t cap, uint64_t value) {
    if (cap == DRM_CLIENT_CAP_ATOMIC) {
        if (!g_kms.atomic) return fail(EOPNOTSUPP);
        g_atomic_cap = value != 0;
    }
    return 0;
}

uint32_t property_id(int, uint32_t object, uint32_t, const char* name) {
    for (size_t i = 0; i < g_props.size(); ++i)
        if (g_props[i].first == object && g_props[i].second == name) return static_cast<uint32_t>(1000 + i);
    g_props.emplace_back(object, name);
    return static_cast<uint32_t>(1000 + g_props.size() - 1);
}

uint32_t primary_plane(int, uint32_t crtc) { return crtc == kCrtc ? kPlane : 0; }

int create_blob(int, const void* data, size_t size, uint32_t* id) {
    if (size != sizeof(drmModeModeInfo)) return fail(EINVAL);
    *id = g_kms.next_blob++;
    std::memcpy(&g_kms.blobs[*id], data, size);
    return 0;
}

int destroy_blob(int, uint32_t id) { return g_kms.blobs.erase(id) ? 0 : fail(ENOENT); }

// Applies an atomic request to the screen (only the properties the kiosk sets).
int atomic_commit(int, const DrmAtomicProp* props, size_t count, uint32_t flags, void* user_data) {
    if (!g_atomic_cap) return fail(EINVAL);
    if (!g_kms.master) return fail(EACCES);
    const bool flip = flags & DRM_MODE_PAGE_FLIP_EVENT;
    if (!g_kms.events.empty()) {
        if (flip) ++g_kms.flip_over_pending;
        return fail(EBUSY);
    }
    Screen next = g_kms.screen;
    bool active = next.on;
    for (size_t i = 0; i < count; ++i) {
        const auto& [object, name] = g_props.at(props[i].property - 1000);
        if (object == kCrtc && name == "MODE_ID") {
            if (props[i].value && !g_kms.blobs.count(static_cast<uint32_t>(props[i].value))) return fail(EINVAL);
            if (props[i].value) next.mode = g_kms.blobs[static_cast<uint32_t>(props[i].value)];
        }
        if (object == kCrtc && name == "ACTIVE") active = props[i].value != 0;
        if (object == kPlane && name == "FB_ID") next.fb = static_cast<uint32_t>(props[i].value);
    }
    if (flags & DRM_MODE_ATOMIC_TEST_ONLY) {
        g_kms.commits.push_back("atomic-test");
        return g_kms.refuse_test_only ? fail(EINVAL) : 0;
    }
    if (flip) {
        if (!(flags & DRM_MODE_ATOMIC_NONBLOCK)) return fail(EINVAL);
        g_kms.commits.push_back("atomic-flip fb " + std::to_string(next.fb));
        g_kms.events.push_back(user_data);
        g_kms.screen.fb = next.fb;
        return 0;
    }
    if (!(flags & DRM_MODE_ATOMIC_ALLOW_MODESET)) return fail(EINVAL);
    if (g_kms.refuse_atomic_restore && next.fb == 7) return fail(EINVAL);
    next.on = active;
    g_kms.commits.push_back(active ? "atomic-mode " + size(next.mode) + " fb " + std::to_string(next.fb)
                                   : "atomic-off");
    g_kms.screen = active ? next : Screen{};
    return 0;
}

int page_flip(int, uint32_t, uint32_t fb, uint32_t flags, void* user_data) {
    if (!g_kms.master) return fail(EACCES);
    if (!g_kms.events.empty()) {
        ++g_kms.flip_over_pending;
        return fail(EBUSY);
    }
    g_kms.commits.push_back("legacy-flip fb " + std::to_string(fb));
    g_kms.screen.fb = fb;
    if (flags & DRM_MODE_PAGE_FLIP_EVENT) g_kms.events.push_back(user_data);
    return 0;
}

int set_master(int) {
    ++g_kms.set_master_calls;
    return g_kms.master ? 0 : fail(EBUSY);
}

std::vector<DrmProbedConnector> probe(int) { return g_kms.connectors; }

const DrmOps kOps = {get_crtc,      free_crtc,   set_crtc,     wait_readable, handle_event, set_client_cap, property_id,
                     primary_plane, create_blob, destroy_blob, atomic_commit, page_flip,    set_master,     probe};

}  // namespace

const DrmOps& ops() { return kOps; }

drmModeModeInfo mode(int width, int height, int hz, bool preferred) {
    drmModeModeInfo m{};
    m.hdisplay = static_cast<uint16_t>(width);
    m.vdisplay = static_cast<uint16_t>(height);
    m.vrefresh = static_cast<uint32_t>(hz);
    m.clock = static_cast<uint32_t>(width * height * hz / 1000);
    if (preferred) m.type = DRM_MODE_TYPE_PREFERRED;
    return m;
}

DrmProbedConnector connector(uint32_t id, bool connected, std::vector<drmModeModeInfo> modes) {
    DrmProbedConnector c;
    c.desc.id = id;
    c.desc.name = "HDMI-A-" + std::to_string(id);
    c.desc.connected = connected;
    c.desc.possible_crtcs = {kCrtc};
    for (const auto& m : modes)
        c.desc.modes.push_back(
            {m.hdisplay, m.vdisplay, static_cast<int>(m.vrefresh), (m.type & DRM_MODE_TYPE_PREFERRED) != 0});
    c.modes = std::move(modes);
    c.mm_width = 500;
    return c;
}

void reset() {
    g_kms = Kms{};
    g_props.clear();
    g_atomic_cap = false;
    g_kms.screen = Screen{7, true, mode(1920, 1080, 60, true)};
    g_kms.connectors = {connector(33, true, {mode(1920, 1080, 60, true), mode(1280, 720, 60)})};
}

int count(const std::string& prefix) {
    int n = 0;
    for (const auto& c : g_kms.commits) n += c.rfind(prefix, 0) == 0;
    return n;
}

}  // namespace body::platform::fake
