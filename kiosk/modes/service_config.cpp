// bodyview's configuration file (contract in service_config.h).
#include "kiosk/modes/service_config.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "shared/input_file.h"

namespace body::kiosk {
namespace {

struct Key {
    const char* key;
    const char* option;  // nullptr: the positional BUNDLE/
};
constexpr Key kKeys[] = {{"bundle", nullptr},
                         {"platform", "platform"},
                         {"rotation", "rotate"},
                         {"display_mode", "mode"},
                         {"device", "device"},
                         {"log_level", "log-level"},
                         {"touch_calibration", "touch-calibration"},
                         {"display_width_mm", "display-width-mm"}};

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// The config path and argv without it; empty path when there is no --config.
Result<std::pair<std::string, std::vector<std::string>>> take_config(const std::vector<std::string>& argv) {
    std::pair<std::string, std::vector<std::string>> out;
    for (size_t i = 0; i < argv.size(); ++i) {
        if (argv[i] == "--config") {
            if (i + 1 >= argv.size()) return input_error("--config needs a FILE");
            out.first = argv[++i];
        } else if (argv[i].rfind("--config=", 0) == 0) {
            out.first = argv[i].substr(9);
        } else {
            out.second.push_back(argv[i]);
        }
    }
    return out;
}

// True when the command line sets `option` itself; nullptr (the bundle): a
// positional, --scene or --model.
bool given(const CliArgs& args, const char* option) {
    if (option) return args.has(option);
    return !args.positional().empty() || args.has("scene") || args.has("model");
}

}  // namespace

Result<std::vector<std::string>> apply_config_file(const std::vector<std::string>& argv,
                                                   const std::set<std::string>& value_options,
                                                   const std::set<std::string>& flag_options) {
    auto taken = take_config(argv);
    if (!taken) return taken.error();
    auto [path, out] = std::move(taken).value();
    if (path.empty()) return out;
    // A directory, FIFO or device is named as such and never opened (a FIFO would block).
    if (Status regular = check_regular_file(path); !regular) return regular.error();
    std::ifstream in(path);
    if (!in) return input_error(path + ": cannot read the configuration file");
    auto command_line = CliArgs::parse(out, value_options, flag_options);
    if (!command_line) return command_line.error();
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        line = trim(line.substr(0, line.find('#')));
        if (line.empty()) continue;
        const size_t eq = line.find('=');
        const std::string where = path + ":" + std::to_string(number) + ": ";
        if (eq == std::string::npos) return input_error(where + "expected 'key = value', got '" + line + "'");
        const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
        const Key* k = std::find_if(std::begin(kKeys), std::end(kKeys), [&](const Key& x) { return key == x.key; });
        if (k == std::end(kKeys))
            return input_error(where + "unknown key '" + key +
                               "' (expected bundle, platform, rotation, display_mode, device, log_level, "
                               "touch_calibration)");
        if (value.empty() || given(command_line.value(), k->option)) continue;
        if (k->option)
            out.push_back(std::string("--") + k->option + "=" + value);
        else
            out.push_back(value);
    }
    return out;
}

}  // namespace body::kiosk
