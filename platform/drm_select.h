#pragma once
// Connector, mode and CRTC selection for the DRM/KMS backend as pure functions
// over plain descriptions (filled from libdrm by drm_surface.cpp, fabricated by
// the unit tests). Follows kmscube: the first connected connector with modes,
// its preferred mode (or the requested WxH[@Hz]), the CRTC it already drives or
// else the first one its encoders can reach.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "shared/error.h"

namespace body::platform {

struct DrmMode {
    int width = 0, height = 0;
    int refresh_hz = 0;  // vrefresh
    bool preferred = false;
};

struct DrmConnector {
    uint32_t id = 0;
    std::string name;  // e.g. "HDMI-A-1"
    bool connected = false;
    std::vector<DrmMode> modes;
    uint32_t current_crtc = 0;             // CRTC driving it now (0: none)
    std::vector<uint32_t> possible_crtcs;  // CRTCs reachable through its encoders, in order
};

// 0 width/height: the preferred mode; 0 refresh: the highest refresh at that size.
struct ModeRequest {
    int width = 0, height = 0, refresh_hz = 0;
};

// Parses "" (preferred), "WxH" or "WxH@Hz".
Result<ModeRequest> parse_mode_request(const std::string& text);

struct DrmSelection {
    size_t connector = 0;  // index into the connector list
    size_t mode = 0;       // index into that connector's modes
    uint32_t crtc = 0;
};

// Picks connector, mode and CRTC; the error names what is missing.
Result<DrmSelection> select_drm_output(std::span<const DrmConnector> connectors, const ModeRequest& request);

}  // namespace body::platform
