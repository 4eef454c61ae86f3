// PLY grammar: G. Turk, "The PLY Polygon File Format", 1994
// (ply / format / element NAME COUNT / property TYPE NAME /
// property list COUNT_TYPE TYPE NAME / comment / obj_info / end_header,
// then each element's rows in order). Contract in ply_check.h.
#include "builder/mesh_import/ply_check.h"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <vector>

#include "shared/atomic_file.h"
#include "shared/input_file.h"

namespace body {
namespace {

constexpr size_t kHeaderLimit = 64 * 1024;

enum class Kind { Int, UInt, Float };
struct Type {
    int size = 0;  // bytes in binary; 0: unknown type
    Kind kind = Kind::Int;
};

Type type_of(const std::string& t) {
    if (t == "char" || t == "int8") return {1, Kind::Int};
    if (t == "uchar" || t == "uint8") return {1, Kind::UInt};
    if (t == "short" || t == "int16") return {2, Kind::Int};
    if (t == "ushort" || t == "uint16") return {2, Kind::UInt};
    if (t == "int" || t == "int32") return {4, Kind::Int};
    if (t == "uint" || t == "uint32") return {4, Kind::UInt};
    if (t == "float" || t == "float32") return {4, Kind::Float};
    if (t == "double" || t == "float64") return {8, Kind::Float};
    return {};
}

struct Property {
    std::string name;
    Type type;  // the value's type (a list's items)
    bool list = false;
    Type count;          // a list's count type
    bool index = false;  // a face's vertex index: must name a row of "vertex"
};

struct Element {
    std::string name;
    unsigned long long count = 0;
    std::vector<Property> properties;
    unsigned long long row_bytes = 0;  // binary: fixed-size properties plus each list's count
    size_t line = 0;
};

struct Header {
    std::string format;
    std::vector<Element> elements;
    size_t body = 0;   // byte offset of the first row
    size_t lines = 0;  // header lines
    unsigned long long vertices = 0;
};

// The header (phase 1): its lines up to end_header, in `header`.
Status parse_header(std::string_view bytes, const std::string& path, Header& header) {
    const std::string_view head = bytes.substr(0, std::min(bytes.size(), kHeaderLimit));
    auto bad = [&](size_t line, const std::string& why) {
        return input_error(path + ": PLY header line " + std::to_string(line) + ": " + why);
    };
    size_t pos = 0, n = 0;
    bool ended = false;
    while (pos < head.size() && !ended) {
        size_t end = head.find('\n', pos);
        if (end == std::string_view::npos) break;  // a header line always ends with a newline
        std::string line(head.substr(pos, end - pos));
        pos = end + 1;
        ++n;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream words(line);
        std::string word;
        words >> word;
        if (n == 1) {
            if (line != "ply") return bad(1, "not a PLY file (no 'ply' magic)");
        } else if (word == "end_header") {
            ended = true;
        } else if (word == "format") {
            words >> header.format;
            if (header.format != "ascii" && header.format != "binary_little_endian" &&
                header.format != "binary_big_endian")
                return bad(n, "unknown format '" + escape_for_message(header.format) + "'");
        } else if (word == "element") {
            Element e;
            std::string count;
            words >> e.name >> count;
            e.line = n;
            if (count.empty() || count.find_first_not_of("0123456789") != std::string::npos || count.size() > 12)
                return bad(n, "element '" + escape_for_message(e.name) + "' count '" + escape_for_message(count) +
                                  "' is not a count");
            e.count = std::stoull(count);
            if (e.name == "vertex") header.vertices = e.count;
            header.elements.push_back(std::move(e));
        } else if (word == "property") {
            if (header.elements.empty()) return bad(n, "property before any element");
            Element& e = header.elements.back();
            Property p;
            std::string type;
            words >> type;
            if (type == "list") {
                std::string count_type, item_type;
                words >> count_type >> item_type >> p.name;
                p.list = true;
                p.count = type_of(count_type);
                p.type = type_of(item_type);
                if (!p.count.size || !p.type.size || p.count.kind == Kind::Float)
                    return bad(n, "unknown list type '" + escape_for_message(count_type + " " + item_type) + "'");
                e.row_bytes += unsigned(p.count.size);
                p.index = e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index");
            } else {
                words >> p.name;
                p.type = type_of(type);
                if (!p.type.size) return bad(n, "unknown property type '" + escape_for_message(type) + "'");
                e.row_bytes += unsigned(p.type.size);
            }
            e.properties.push_back(std::move(p));
        } else if (word != "comment" && word != "obj_info" && !word.empty()) {
            return bad(n, "unknown keyword '" + escape_for_message(word) + "'");
        }
    }
    if (!ended) return bad(n, "no end_header in the first " + std::to_string(head.size()) + " bytes");
    if (header.format.empty()) return bad(n, "no format line");
    header.body = pos;
    header.lines = n;
    const uint64_t body = bytes.size() - pos;
    for (const Element& e : header.elements) {
        const unsigned long long row = header.format == "ascii" ? 2 : e.row_bytes;
        if (row > 0 && e.count > body / row)
            return bad(e.line, "declares " + std::to_string(e.count) + " rows, more than the " + std::to_string(body) +
                                   " bytes after the header can hold");
    }
    return ok_status();
}

enum class Role { Value, Count, Index };

// Why a value of type `t` in role `role` is out of place ("" when it is fine).
std::string value_fault(double v, Type t, Role role, unsigned long long vertices) {
    if (t.kind == Kind::Float) {
        if (!std::isfinite(v) || (t.size == 4 && std::fabs(v) > 3.4028234663852886e38)) return "is not a finite float";
    } else {
        const double bits = 8.0 * t.size;
        const double lo = t.kind == Kind::Int ? -std::ldexp(1.0, int(bits) - 1) : 0.0;
        const double hi = std::ldexp(1.0, int(bits) - (t.kind == Kind::Int ? 1 : 0)) - 1;
        if (v < lo || v > hi) return "is outside its type's range";
    }
    if (role == Role::Count && v < 0) return "is negative";
    if (role == Role::Index && (v < 0 || v >= double(vertices)))
        return "is not a vertex index (0.." + std::to_string(vertices ? vertices - 1 : 0) + ")";
    return {};
}

// ASCII rows (phase 2a): one row a line, tokens matching the properties.
Status walk_ascii(std::string_view bytes, const std::string& path, const Header& h) {
    size_t pos = h.body, line_no = h.lines;
    std::vector<std::string_view> tok;
    auto next_line = [&]() {  // the next line with any token; false at the end
        while (pos < bytes.size()) {
            size_t end = bytes.find('\n', pos);
            if (end == std::string_view::npos) end = bytes.size();
            const std::string_view line = bytes.substr(pos, end - pos);
            pos = end + 1;
            ++line_no;
            split_words(line, tok);
            if (!tok.empty()) return true;
        }
        return false;
    };
    for (const Element& e : h.elements) {
        for (unsigned long long r = 0; r < e.count; ++r) {
            auto bad = [&](const std::string& why) {
                return input_error(path + ": PLY line " + std::to_string(line_no) + " (element '" +
                                   escape_for_message(e.name) + "' row " + std::to_string(r + 1) + "): " + why);
            };
            if (!next_line())
                return bad("missing: the file ends after " + std::to_string(r) + " of " + std::to_string(e.count) +
                           " rows");
            size_t t = 0;
            auto value = [&](Type type, Role role, const std::string& what, double& v) -> Status {
                const std::string word(tok[t++]);
                char* stop = nullptr;
                errno = 0;
                v = type.kind == Kind::Float ? std::strtod(word.c_str(), &stop)
                                             : double(std::strtoll(word.c_str(), &stop, 10));
                if (stop == word.c_str() || *stop != '\0' || errno == ERANGE)
                    return bad(what + " '" + escape_for_message(word, 40) + "' is not a number of its type");
                if (std::string why = value_fault(v, type, role, h.vertices); !why.empty())
                    return bad(what + " " + escape_for_message(word, 40) + " " + why);
                return ok_status();
            };
            for (const Property& p : e.properties) {
                std::string what = "'";
                what.append(escape_for_message(p.name)).append("'");
                std::string first = what;
                if (p.list) first.insert(0, "list count ");
                if (t >= tok.size())
                    return bad("the row has " + std::to_string(tok.size()) + " values; property " + what + " has none");
                double v = 0;
                if (Status s = value(p.list ? p.count : p.type, p.list ? Role::Count : Role::Value, first, v); !s)
                    return s;
                const size_t items = p.list ? size_t(v) : 0;
                if (p.list && items > tok.size() - t)
                    return bad("list " + what + " declares " + std::to_string(items) + " values, the row holds " +
                               std::to_string(tok.size() - t));
                for (size_t k = 0; k < items; ++k)
                    if (Status s = value(p.type, p.index ? Role::Index : Role::Value, what + " value", v); !s) return s;
            }
            if (t != tok.size())
                return bad("the row has " + std::to_string(tok.size()) + " values, its properties take " +
                           std::to_string(t));
        }
    }
    if (next_line())
        return input_error(path + ": PLY line " + std::to_string(line_no) + ": data after the last element's rows");
    return ok_status();
}

template <typename T>
T native(const unsigned char* b) {
    T v;
    std::memcpy(&v, b, sizeof v);
    return v;
}

// One binary value of type `t` at `p` (file byte order `big`).
double read_binary(const char* p, Type t, bool big) {
    unsigned char b[8];
    std::memcpy(b, p, size_t(t.size));
    if (big != (std::endian::native == std::endian::big))
        for (int i = 0; i < t.size / 2; ++i) std::swap(b[i], b[t.size - 1 - i]);
    switch (t.kind) {
        case Kind::Float: return t.size == 4 ? double(native<float>(b)) : native<double>(b);
        case Kind::Int:
            if (t.size == 1) return double(std::bit_cast<int8_t>(b[0]));
            if (t.size == 2) return double(native<int16_t>(b));
            return double(native<int32_t>(b));
        case Kind::UInt:
            if (t.size == 1) return double(b[0]);
            if (t.size == 2) return double(native<uint16_t>(b));
            return double(native<uint32_t>(b));
    }
    return 0;
}

// Binary rows (phase 2b): the rows' bytes, exactly to the file's end.
Status walk_binary(std::string_view bytes, const std::string& path, const Header& h) {
    const bool big = h.format == "binary_big_endian";
    size_t pos = h.body;
    for (const Element& e : h.elements) {
        // An element without properties has rows of no bytes: nothing to walk (its count may be 10^12).
        const unsigned long long rows = e.properties.empty() ? 0 : e.count;
        for (unsigned long long r = 0; r < rows; ++r) {
            const size_t row_start = pos;
            auto bad = [&](size_t at, const std::string& why) {
                return input_error(path + ": PLY byte " + std::to_string(at) + " (element '" +
                                   escape_for_message(e.name) + "' row " + std::to_string(r + 1) + "): " + why);
            };
            auto value = [&](Type t, Role role, const std::string& what, double& v) -> Status {
                if (bytes.size() - pos < size_t(t.size))
                    return bad(row_start, "the file ends inside the row (" + std::to_string(r) + " of " +
                                              std::to_string(e.count) + " rows complete)");
                v = read_binary(bytes.data() + pos, t, big);
                if (std::string why = value_fault(v, t, role, h.vertices); !why.empty()) {
                    std::ostringstream shown;
                    shown << v;
                    return bad(pos, what + " " + shown.str() + " " + why);
                }
                pos += size_t(t.size);
                return ok_status();
            };
            for (const Property& p : e.properties) {
                std::string what = "'";
                what.append(escape_for_message(p.name)).append("'");
                std::string first = what;
                if (p.list) first.insert(0, "list count ");
                double v = 0;
                if (Status s = value(p.list ? p.count : p.type, p.list ? Role::Count : Role::Value, first, v); !s)
                    return s;
                for (size_t k = 0, items = p.list ? size_t(v) : 0; k < items; ++k)
                    if (Status s = value(p.type, p.index ? Role::Index : Role::Value, what + " value", v); !s) return s;
            }
        }
    }
    if (pos != bytes.size())
        return input_error(path + ": PLY byte " + std::to_string(pos) + ": " + std::to_string(bytes.size() - pos) +
                           " bytes after the last element's rows");
    return ok_status();
}

}  // namespace

Status check_ply_bytes(std::string_view bytes, const std::string& path) {
    Header header;
    if (Status s = parse_header(bytes, path, header); !s) return s;
    return header.format == "ascii" ? walk_ascii(bytes, path, header) : walk_binary(bytes, path, header);
}

Status check_ply_file(const std::string& path) {
    auto bytes = read_file(path);  // checks for a regular file first
    if (!bytes) return bytes.error();
    return check_ply_bytes(*bytes, path);
}

}  // namespace body
