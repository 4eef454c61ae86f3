// Label table parsing: MRIcron/AAL .txt, FSL/FSLeyes .lut, FreeSurfer-style
// colour tables, ITK-SNAP label descriptions and MRIcron's binary 768-byte .lut.
#include "builder/import/label_table.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "shared/atomic_file.h"
#include "shared/text_lines.h"

namespace body {
namespace {

constexpr size_t kBinaryLutSize = 768;

std::vector<std::string> split_tokens(const std::string& line) {
    std::vector<std::string> out;
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t') ++j;
        if (j > i) out.push_back(line.substr(i, j - i));
        i = j;
    }
    return out;
}

std::optional<int64_t> parse_int(const std::string& s) {
    int64_t v = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
    return v;
}

std::optional<double> parse_real(const std::string& s) {
    if (s.empty()) return std::nullopt;
    const char* begin = s.c_str();
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(begin, &end);
    if (end != begin + s.size() || errno != 0 || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::string join(const std::vector<std::string>& tokens, size_t first, size_t last) {
    std::string out;
    for (size_t i = first; i < last; ++i) {
        if (!out.empty()) out += ' ';
        out += tokens[i];
    }
    return out;
}

bool is_binary_lut(const std::string& bytes) {
    if (bytes.size() != kBinaryLutSize) return false;
    for (unsigned char c : bytes) {
        if (c < 0x20 && c != '\n' && c != '\r' && c != '\t') return true;
        if (c >= 0x7f) return true;
    }
    return false;
}

LabelTable parse_binary_lut(const std::string& bytes) {
    LabelTable table;
    for (int64_t i = 1; i < 256; ++i) {
        const auto at = [&](size_t k) { return static_cast<double>(static_cast<unsigned char>(bytes[k])) / 255.0; };
        const size_t u = static_cast<size_t>(i);
        table.entries[i].color = Vec3(at(u), at(256 + u), at(512 + u));
    }
    return table;
}

// One text line, already split; fills `entry` or returns a reason.
std::string parse_line(const std::vector<std::string>& t, LabelEntry& entry) {
    if (t.size() < 2) return "expected 'index name'";
    // FSL/FSLeyes: index r g b name... with r, g, b in [0, 1].
    if (t.size() >= 5) {
        auto r = parse_real(t[1]), g = parse_real(t[2]), b = parse_real(t[3]);
        if (r && g && b && !parse_real(t[4])) {
            for (double c : {*r, *g, *b}) {
                if (c < 0.0 || c > 1.0) return "colour component " + std::to_string(c) + " outside [0, 1]";
            }
            entry.name = join(t, 4, t.size());
            entry.color = Vec3(*r, *g, *b);
            return {};
        }
    }
    // index name... [numbers]: trailing numbers are a code (1), r g b (3) or r g b a (4).
    size_t name_end = t.size();
    while (name_end > 2 && parse_real(t[name_end - 1])) --name_end;
    const size_t trailing = t.size() - name_end;
    if (parse_real(t[1]) && name_end == 2 && trailing > 0) return "missing name";
    entry.name = join(t, 1, name_end);
    if (trailing == 3 || trailing == 4) {
        double c[3];
        bool all_bytes = true;
        for (size_t k = 0; k < 3; ++k) {
            auto v = parse_int(t[name_end + k]);
            if (!v || *v < 0 || *v > 255)
                all_bytes = false;
            else
                c[k] = static_cast<double>(*v) / 255.0;
        }
        if (all_bytes) entry.color = Vec3(c[0], c[1], c[2]);
    }
    return {};
}

// ITK-SNAP label description: `index r g b alpha visible mesh-visible "name"`,
// r g b 0-255. Returns a reason, or "" with `entry` filled.
std::string parse_itksnap_line(const std::string& line, LabelEntry& entry) {
    const size_t open = line.find('"'), close = line.rfind('"');
    if (close == open) return "unterminated quoted name";
    const auto t = split_tokens(line.substr(0, open));
    if (t.size() != 7) return "expected 'index r g b alpha visible mesh \"name\"' (ITK-SNAP)";
    double c[3];
    for (size_t k = 0; k < 3; ++k) {
        auto v = parse_int(t[k + 1]);
        if (!v || *v < 0 || *v > 255) return "colour component '" + t[k + 1] + "' is not 0-255";
        c[k] = static_cast<double>(*v) / 255.0;
    }
    entry.name = line.substr(open + 1, close - open - 1);
    entry.color = Vec3(c[0], c[1], c[2]);
    return {};
}

}  // namespace

Result<LabelTable> parse_label_table(const std::string& text, const std::string& path) {
    if (is_binary_lut(text)) return parse_binary_lut(text);
    LabelTable table;
    Status walked = for_each_text_line(text, path, [&](std::string& line, const std::string& where) -> Status {
        const size_t hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        const auto tokens = split_tokens(line);
        if (tokens.empty()) return ok_status();
        for (char c : line) {
            if (c == '\0') return input_error(where + "binary data in a text label table");
        }
        auto index = parse_int(tokens[0]);
        if (!index) return input_error(where + "label index '" + tokens[0] + "' is not an integer");
        if (*index < 0) return input_error(where + "negative label index " + tokens[0]);
        LabelEntry entry;
        const bool quoted = line.find('"') != std::string::npos;
        const std::string reason = quoted ? parse_itksnap_line(line, entry) : parse_line(tokens, entry);
        if (!reason.empty()) return input_error(where + reason);
        if (entry.name.empty()) return input_error(where + "missing name");
        if (!table.entries.emplace(*index, std::move(entry)).second) {
            return input_error(where + "duplicate label index " + tokens[0]);
        }
        return ok_status();
    });
    if (!walked) return walked.error();
    if (table.entries.empty()) return input_error(path + ": no labels in the table");
    return table;
}

Result<LabelTable> read_label_table(const std::string& path) {
    auto text = read_file(path);
    if (!text) return text.error();
    return parse_label_table(*text, path);
}

void merge_label_table(LabelTable& base, const LabelTable& extra) {
    for (const auto& [index, entry] : extra.entries) {
        auto it = base.entries.find(index);
        if (it == base.entries.end()) {
            base.entries.emplace(index, entry);
            continue;
        }
        if (it->second.name.empty()) it->second.name = entry.name;
        if (!it->second.color) it->second.color = entry.color;
    }
}

}  // namespace body
