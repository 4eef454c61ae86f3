#pragma once
// How much bodyview says on stderr (the journal under systemd): `--log-level`,
// `log_level` in the service's config. Errors and warnings are always printed;
// info lines (devices found, added, removed) from Info on; timing lines at Debug.
#include <string>

#include "shared/error.h"

namespace body::platform {

enum class LogLevel { Error, Warning, Info, Debug };

void set_log_level(LogLevel level);
LogLevel log_level();
inline bool log_enabled(LogLevel level) { return static_cast<int>(level) <= static_cast<int>(log_level()); }
Result<LogLevel> parse_log_level(const std::string& text);

}  // namespace body::platform
