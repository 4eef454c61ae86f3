#include "shared/cli_args.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace body {

Result<CliArgs> CliArgs::parse(const std::vector<std::string>& argv, const std::set<std::string>& value_options,
                               const std::set<std::string>& flag_options) {
    CliArgs args;
    for (size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.size() > 2 && a.starts_with("--")) {
            std::string name = a.substr(2), value;
            bool inline_value = false;
            if (auto eq = name.find('='); eq != std::string::npos) {
                value = name.substr(eq + 1);
                name = name.substr(0, eq);
                inline_value = true;
            }
            if (value_options.count(name)) {
                if (!inline_value) {
                    if (i + 1 >= argv.size()) return input_error("option --" + name + " needs a value");
                    value = argv[++i];
                }
                args.options_.emplace_back(name, value);
            } else if (flag_options.count(name) && !inline_value) {
                args.options_.emplace_back(name, "");
            } else {
                return input_error("unknown option --" + name);
            }
        } else if (a == "-o" && value_options.count("output")) {
            if (i + 1 >= argv.size()) return input_error("option -o needs a value");
            if (argv[i + 1].empty()) return input_error("option -o: the output path is empty");
            args.options_.emplace_back("output", argv[++i]);
        } else if (a.size() > 1 && a[0] == '-' && !(std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.')) {
            return input_error("unknown option " + a);
        } else {
            args.positional_.push_back(a);
        }
    }
    return args;
}

bool CliArgs::has(const std::string& name) const {
    for (const auto& [k, v] : options_)
        if (k == name) return true;
    return false;
}

std::optional<std::string> CliArgs::get(const std::string& name) const {
    std::optional<std::string> found;
    for (const auto& [k, v] : options_)
        if (k == name) found = v;  // last one wins
    return found;
}

std::string CliArgs::get_or(const std::string& name, const std::string& fallback) const {
    auto v = get(name);
    return v ? *v : fallback;
}

Result<double> CliArgs::get_double(const std::string& name, double fallback) const {
    auto v = get(name);
    if (!v) return fallback;
    char* end = nullptr;
    errno = 0;
    double d = std::strtod(v->c_str(), &end);
    if (v->empty() || *end != '\0' || errno != 0 || !std::isfinite(d))
        return input_error("option --" + name + ": '" + *v + "' is not a number");
    return d;
}

Result<long> CliArgs::get_long(const std::string& name, long fallback) const {
    auto v = get(name);
    if (!v) return fallback;
    char* end = nullptr;
    errno = 0;
    long n = std::strtol(v->c_str(), &end, 10);
    if (v->empty() || *end != '\0' || errno != 0)
        return input_error("option --" + name + ": '" + *v + "' is not an integer");
    return n;
}

Result<unsigned> CliArgs::get_jobs(unsigned fallback) const {
    auto n = get_long("jobs", static_cast<long>(fallback));
    if (!n) return n.error();
    if (has("jobs") && (*n < 1 || *n > 256)) return input_error("option --jobs: must be between 1 and 256");
    return static_cast<unsigned>(*n);
}

}  // namespace body
