#pragma once
// bodyview's configuration file for the service (`bodyview --config FILE`, the
// packaged unit reads /etc/bodyview/bodyview.conf): "key = value" lines, '#'
// starts a comment, an empty value leaves the default. Keys and the options
// they stand for:
//   bundle             BUNDLE/ (the exhibit)          rotation      --rotate
//   platform           --platform                     display_mode  --mode
//   device             --device                       log_level     --log-level
//   touch_calibration  --touch-calibration (six numbers, platform/evdev_touch.h)
// Options given on the command line win over the file. Errors name the file and
// line (exit 2).
#include <set>
#include <string>
#include <vector>

#include "shared/cli_args.h"
#include "shared/error.h"

namespace body::kiosk {

// `argv` (without the program name) with `--config FILE` (or `--config=FILE`)
// replaced by the file's options that the command line does not give itself;
// argv unchanged when it has no --config. The option sets are bodyview's (to
// tell what the command line gives).
Result<std::vector<std::string>> apply_config_file(const std::vector<std::string>& argv,
                                                   const std::set<std::string>& value_options,
                                                   const std::set<std::string>& flag_options);

}  // namespace body::kiosk
