// Pure KMS output selection (see drm_select.h); after kmscube's drm-common.c.
#include "platform/drm_select.h"

#include <cstdio>

namespace body::platform {
namespace {

std::string mode_text(const DrmMode& m) {
    return std::to_string(m.width) + "x" + std::to_string(m.height) + "@" + std::to_string(m.refresh_hz);
}

// Preferred-flagged mode, else the largest (then fastest) one.
size_t default_mode(const std::vector<DrmMode>& modes) {
    for (size_t i = 0; i < modes.size(); ++i)
        if (modes[i].preferred) return i;
    size_t best = 0;
    for (size_t i = 1; i < modes.size(); ++i) {
        long area = static_cast<long>(modes[i].width) * modes[i].height;
        long best_area = static_cast<long>(modes[best].width) * modes[best].height;
        if (area > best_area || (area == best_area && modes[i].refresh_hz > modes[best].refresh_hz)) best = i;
    }
    return best;
}

Result<size_t> requested_mode(const DrmConnector& c, const ModeRequest& r) {
    long found = -1;
    for (size_t i = 0; i < c.modes.size(); ++i) {
        const DrmMode& m = c.modes[i];
        if (m.width != r.width || m.height != r.height) continue;
        if (r.refresh_hz != 0 && m.refresh_hz != r.refresh_hz) continue;
        if (found < 0 || m.refresh_hz > c.modes[static_cast<size_t>(found)].refresh_hz) found = static_cast<long>(i);
    }
    if (found >= 0) return static_cast<size_t>(found);
    std::string list;
    for (const DrmMode& m : c.modes) {
        if (!list.empty()) list.append(", ");
        list.append(mode_text(m));
    }
    std::string want = std::to_string(r.width) + "x" + std::to_string(r.height);
    if (r.refresh_hz) want.append("@").append(std::to_string(r.refresh_hz));
    return input_error("drm: connector " + c.name + " has no mode " + want + " (has " + list + ")");
}

}  // namespace

Result<ModeRequest> parse_mode_request(const std::string& text) {
    ModeRequest r;
    if (text.empty()) return r;
    char x = 0, at = 0, extra = 0;
    int n = std::sscanf(text.c_str(), "%d%c%d%c%d%c", &r.width, &x, &r.height, &at, &r.refresh_hz, &extra);
    bool ok =
        (n == 3 || (n == 5 && at == '@')) && (x == 'x' || x == 'X') && r.width > 0 && r.height > 0 && r.refresh_hz >= 0;
    if (!ok) return input_error("bad mode '" + text + "' (expected WxH or WxH@Hz, e.g. 1920x1080@60)");
    return r;
}

Result<DrmSelection> select_drm_output(std::span<const DrmConnector> connectors, const ModeRequest& request) {
    if (connectors.empty()) return runtime_error("drm: the device has no connectors");
    long chosen = -1;
    for (size_t i = 0; i < connectors.size() && chosen < 0; ++i)
        if (connectors[i].connected && !connectors[i].modes.empty()) chosen = static_cast<long>(i);
    if (chosen < 0) return runtime_error("drm: no connected connector with modes (is a display plugged in?)");
    DrmSelection sel;
    sel.connector = static_cast<size_t>(chosen);
    const DrmConnector& c = connectors[sel.connector];
    if (request.width > 0) {
        auto m = requested_mode(c, request);
        if (!m) return m.error();
        sel.mode = m.value();
    } else {
        sel.mode = default_mode(c.modes);
    }
    if (c.current_crtc != 0) {
        sel.crtc = c.current_crtc;
    } else if (!c.possible_crtcs.empty()) {
        sel.crtc = c.possible_crtcs.front();
    } else {
        return runtime_error("drm: no CRTC can drive connector " + c.name);
    }
    return sel;
}

}  // namespace body::platform
