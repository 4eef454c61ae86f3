// KMS connector/mode/CRTC selection on fabricated connector descriptions.
#include "platform/drm_select.h"

#include <gtest/gtest.h>

using namespace body::platform;

namespace {

DrmConnector hdmi(bool connected, std::vector<DrmMode> modes, uint32_t current = 0,
                  std::vector<uint32_t> crtcs = {41, 42}) {
    DrmConnector c;
    c.id = 77;
    c.name = "HDMI-A-1";
    c.connected = connected;
    c.modes = std::move(modes);
    c.current_crtc = current;
    c.possible_crtcs = std::move(crtcs);
    return c;
}

const std::vector<DrmMode> kModes = {{1920, 1080, 60, false},
                                     {1280, 720, 60, false},
                                     {1920, 1080, 50, false},
                                     {3840, 2160, 30, true},
                                     {1280, 720, 75, false}};

// The selection for `list`, which must succeed.
DrmSelection selected(const std::vector<DrmConnector>& list, const ModeRequest& request = {}) {
    auto sel = select_drm_output(list, request);
    EXPECT_TRUE(sel.ok()) << (sel.ok() ? std::string() : sel.error().message);
    return sel.ok() ? *sel : DrmSelection{};
}

}  // namespace

TEST(DrmSelect, PicksTheFirstConnectedConnectorWithModes) {
    std::vector<DrmConnector> list = {hdmi(false, kModes), hdmi(true, {}), hdmi(true, kModes)};
    list[2].name = "DSI-1";
    EXPECT_EQ(selected(list).connector, 2u);
}

TEST(DrmSelect, PreferredModeByDefault) {
    std::vector<DrmConnector> list = {hdmi(true, kModes)};
    const DrmMode& mode = list[0].modes[selected(list).mode];
    EXPECT_EQ(mode.width, 3840);
    EXPECT_EQ(mode.refresh_hz, 30);
}

TEST(DrmSelect, WithoutAPreferredFlagTakesTheLargestThenFastest) {
    std::vector<DrmMode> modes = {{1280, 720, 60, false}, {1920, 1080, 50, false}, {1920, 1080, 60, false}};
    std::vector<DrmConnector> list = {hdmi(true, modes)};
    EXPECT_EQ(selected(list).mode, 2u);
}

TEST(DrmSelect, RequestedSizePicksTheHighestRefreshAtThatSize) {
    std::vector<DrmConnector> list = {hdmi(true, kModes)};
    EXPECT_EQ(selected(list, {1280, 720, 0}).mode, 4u);
    EXPECT_EQ(selected(list, {1920, 1080, 50}).mode, 2u);
}

TEST(DrmSelect, MissingRequestedModeNamesWhatExists) {
    std::vector<DrmConnector> list = {hdmi(true, kModes)};
    auto sel = select_drm_output(list, {800, 480, 0});
    ASSERT_FALSE(sel.ok());
    EXPECT_NE(sel.error().message.find("800x480"), std::string::npos);
    EXPECT_NE(sel.error().message.find("1920x1080@60"), std::string::npos);
    EXPECT_NE(sel.error().message.find("HDMI-A-1"), std::string::npos);
    EXPECT_EQ(sel.error().message.find('\n'), std::string::npos);
}

TEST(DrmSelect, KeepsTheCrtcAlreadyDrivingTheConnector) {
    std::vector<DrmConnector> list = {hdmi(true, kModes, 42)};
    EXPECT_EQ(selected(list).crtc, 42u);
    list[0].current_crtc = 0;
    EXPECT_EQ(selected(list).crtc, 41u);
}

TEST(DrmSelect, FailsClearlyWithoutDisplayOrCrtc) {
    std::vector<DrmConnector> none;
    EXPECT_FALSE(select_drm_output(none, {}).ok());
    std::vector<DrmConnector> unplugged = {hdmi(false, kModes)};
    auto r = select_drm_output(unplugged, {});
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("connected"), std::string::npos);
    std::vector<DrmConnector> no_crtc = {hdmi(true, kModes, 0, {})};
    EXPECT_FALSE(select_drm_output(no_crtc, {}).ok());
}

TEST(DrmSelect, ParsesModeRequests) {
    auto a = parse_mode_request("1920x1080@60");
    ASSERT_TRUE(a.ok());
    EXPECT_EQ(a->width, 1920);
    EXPECT_EQ(a->height, 1080);
    EXPECT_EQ(a->refresh_hz, 60);
    auto b = parse_mode_request("800x480");
    ASSERT_TRUE(b.ok());
    EXPECT_EQ(b->refresh_hz, 0);
    auto c = parse_mode_request("");
    ASSERT_TRUE(c.ok());
    EXPECT_EQ(c->width, 0);
    for (const char* bad : {"1920", "1920x", "x1080", "1920x1080@", "1920x1080@60Hz", "0x0", "-5x3", "axb"})
        EXPECT_FALSE(parse_mode_request(bad).ok()) << bad;
}
