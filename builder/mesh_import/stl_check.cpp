// STL: 3D Systems' StereoLithography Interface Specification (1989): binary =
// 80-byte header, uint32 count, 50 bytes a triangle (normal, 3 vertices as
// little-endian float32, uint16 attribute); ASCII = the grammar in
// stl_check.h. Contract in stl_check.h.
#include "builder/mesh_import/stl_check.h"

#include <bit>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "shared/atomic_file.h"
#include "shared/input_file.h"

namespace body {
namespace {

constexpr double kFloatMax = 3.4028234663852886e38;

bool is_text(std::string_view bytes) {
    for (unsigned char c : bytes)
        if (c == 0x7f || (c < 0x20 && !std::isspace(c))) return false;
    return true;
}

bool starts_with_solid(std::string_view bytes) {
    size_t i = 0;
    while (i < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[i]))) ++i;
    return bytes.substr(i, 5) == "solid";
}

// Whitespace-separated words with their line numbers.
struct Words {
    std::string_view text;
    size_t pos = 0, line = 1;
    std::string_view next() {
        while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos])))
            if (text[pos++] == '\n') ++line;
        const size_t start = pos;
        while (pos < text.size() && !std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
        return text.substr(start, pos - start);
    }
    void skip_line() {  // a solid's name
        while (pos < text.size() && text[pos] != '\n') ++pos;
    }
};

Status check_ascii(std::string_view bytes, const std::string& path) {
    Words w{bytes};
    auto bad = [&](const std::string& why) {
        return input_error(path + ": STL line " + std::to_string(w.line) + ": " + why);
    };
    auto shown = [](std::string_view word) {
        if (word.empty()) return std::string("the end of the file");
        std::string quoted = "'";
        return quoted.append(escape_for_message(word, 40)).append("'");
    };
    auto expect = [&](const char* keyword) -> Status {
        const std::string_view word = w.next();
        if (word != keyword) return bad(std::string("expected '") + keyword + "', found " + shown(word));
        return ok_status();
    };
    auto numbers = [&](const char* what) -> Status {
        for (int k = 0; k < 3; ++k) {
            const std::string word(w.next());
            char* stop = nullptr;
            const double v = std::strtod(word.c_str(), &stop);
            if (word.empty() || *stop != '\0') return bad(std::string(what) + " needs 3 numbers, found " + shown(word));
            if (!std::isfinite(v) || std::fabs(v) > kFloatMax)
                return bad(std::string(what) + " value '" + escape_for_message(word, 40) + "' is not a finite float");
        }
        return ok_status();
    };
    size_t solids = 0, facets = 0;
    for (std::string_view word = w.next(); !word.empty(); word = w.next(), ++solids) {
        if (word != "solid") return bad("expected 'solid' or the end of the file, found " + shown(word));
        w.skip_line();
        for (word = w.next(); word != "endsolid"; word = w.next()) {
            if (word != "facet") return bad("expected 'facet' or 'endsolid', found " + shown(word));
            if (Status s = expect("normal"); !s) return s;
            if (Status s = numbers("facet normal"); !s) return s;
            if (Status s = expect("outer"); !s) return s;
            if (Status s = expect("loop"); !s) return s;
            for (int v = 0; v < 3; ++v) {
                if (Status s = expect("vertex"); !s)
                    return bad("facet has " + std::to_string(v) + " vertices, an STL facet has 3");
                if (Status s = numbers("vertex"); !s) return s;
            }
            if (const std::string_view end = w.next(); end != "endloop")
                return bad(end == "vertex" ? std::string("facet has more than 3 vertices, an STL facet has 3")
                                           : "expected 'endloop', found " + shown(end));
            if (Status s = expect("endfacet"); !s) return s;
            ++facets;
        }
        w.skip_line();
    }
    if (facets == 0) return bad("no facets");
    return ok_status();
}

uint32_t little_u32(const char* p) {
    const auto* b = reinterpret_cast<const unsigned char*>(p);
    return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}

Status check_binary(std::string_view bytes, const std::string& path) {
    if (bytes.size() < 84)
        return input_error(path + ": binary STL: " + std::to_string(bytes.size()) +
                           " bytes, less than its 84-byte header and triangle count");
    const uint32_t count = little_u32(bytes.data() + 80);
    if (count == 0) return input_error(path + ": STL byte 80: binary STL declares no triangles");
    const uint64_t need = 84 + 50 * uint64_t(count);
    if (need != bytes.size())
        return input_error(path + ": STL byte 80: binary STL declares " + std::to_string(count) + " triangles (" +
                           std::to_string(need) + " bytes), the file has " + std::to_string(bytes.size()) + " bytes");
    for (uint64_t t = 0; t < count; ++t) {
        for (int k = 3; k < 12; ++k) {  // the 3 vertices after the normal
            const size_t at = size_t(84 + 50 * t + 4 * uint64_t(k));
            const float v = std::bit_cast<float>(little_u32(bytes.data() + at));
            if (!std::isfinite(v)) {
                std::ostringstream s;
                s << v;
                return input_error(path + ": STL byte " + std::to_string(at) + " (triangle " + std::to_string(t + 1) +
                                   "): vertex coordinate " + s.str() + " is not finite");
            }
        }
    }
    return ok_status();
}

}  // namespace

Status check_stl_bytes(std::string_view bytes, const std::string& path) {
    if (starts_with_solid(bytes) && is_text(bytes)) return check_ascii(bytes, path);
    return check_binary(bytes, path);
}

Status check_stl_file(const std::string& path) {
    auto bytes = read_file(path);  // checks for a regular file first
    if (!bytes) return bytes.error();
    return check_stl_bytes(*bytes, path);
}

}  // namespace body
