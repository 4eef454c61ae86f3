#pragma once
// A small command-line parser shared by bodygen and bodyview: positional
// arguments, `--flag`, `--key value` and `--key=value`. Unknown options are
// errors so that a typo never silently changes a build.
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "shared/error.h"

namespace body {

class CliArgs {
public:
    // `value_options` take a value; `flag_options` do not. Names without "--".
    static Result<CliArgs> parse(const std::vector<std::string>& argv, const std::set<std::string>& value_options,
                                 const std::set<std::string>& flag_options);

    const std::vector<std::string>& positional() const { return positional_; }
    bool has(const std::string& name) const;
    std::optional<std::string> get(const std::string& name) const;
    std::string get_or(const std::string& name, const std::string& fallback) const;
    // Numeric accessors: an unparsable value is a usage error naming the option.
    Result<double> get_double(const std::string& name, double fallback) const;
    Result<long> get_long(const std::string& name, long fallback) const;
    // `--jobs N`: threads, 1 to 256; `fallback` when the option is absent.
    Result<unsigned> get_jobs(unsigned fallback) const;

private:
    std::vector<std::string> positional_;
    std::vector<std::pair<std::string, std::string>> options_;
};

}  // namespace body
