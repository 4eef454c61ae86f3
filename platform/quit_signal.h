#pragma once
// SIGINT and SIGTERM as a quit request the surfaces report through
// poll_events() (platform.h): the kiosk loop then leaves by its normal path, so
// the display is restored and systemd hears STOPPING=1. A second signal while
// the first is pending falls back to the default action (a stuck loop still dies).
namespace body::platform {

// Installs the handlers (idempotent) and clears an earlier request.
void install_quit_handlers();
bool quit_requested();
// Restores the default actions (the surface is closing).
void remove_quit_handlers();

}  // namespace body::platform
