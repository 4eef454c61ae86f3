// PLY header grammar: G. Turk, "The PLY Polygon File Format", 1994
// (ply / format / element NAME COUNT / property TYPE NAME /
// property list COUNT_TYPE TYPE NAME / comment / obj_info / end_header).
#include "builder/mesh_import/ply_header.h"

#include <fstream>
#include <sstream>
#include <vector>

#include "shared/input_file.h"

namespace body {
namespace {

constexpr size_t kHeaderLimit = 64 * 1024;

int type_size(const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
}

struct Element {
    unsigned long long count = 0;
    unsigned long long row_bytes = 0;  // binary: fixed-size properties plus each list's count
    size_t line = 0;
};

}  // namespace

Status check_ply_header(const std::string& path) {
    auto size = regular_file_size(path);
    if (!size) return size.error();
    std::ifstream in(path, std::ios::binary);
    if (!in) return input_error(path + ": cannot open");
    std::string head(std::min<uint64_t>(*size, kHeaderLimit), '\0');
    in.read(head.data(), std::streamsize(head.size()));
    auto bad = [&](size_t line, const std::string& why) {
        return input_error(path + ": PLY header line " + std::to_string(line) + ": " + why);
    };
    std::istringstream lines(head);
    std::string line, format;
    std::vector<Element> elements;
    size_t n = 0;
    bool ended = false;
    while (std::getline(lines, line)) {
        ++n;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream words(line);
        std::string word;
        words >> word;
        if (n == 1) {
            if (line != "ply") return bad(1, "not a PLY file (no 'ply' magic)");
            continue;
        }
        if (word == "end_header") {
            ended = true;
            break;
        }
        if (word == "format") {
            words >> format;
            if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
                return bad(n, "unknown format '" + escape_for_message(format) + "'");
        } else if (word == "element") {
            std::string name, count;
            words >> name >> count;
            Element e;
            e.line = n;
            if (count.empty() || count.find_first_not_of("0123456789") != std::string::npos || count.size() > 12)
                return bad(n, "element '" + escape_for_message(name) + "' count '" + escape_for_message(count) +
                                  "' is not a count");
            e.count = std::stoull(count);
            elements.push_back(e);
        } else if (word == "property") {
            if (elements.empty()) return bad(n, "property before any element");
            std::string type;
            words >> type;
            if (type == "list") {
                std::string count_type, item_type;
                words >> count_type >> item_type;
                if (!type_size(count_type) || !type_size(item_type))
                    return bad(n, "unknown list type '" + escape_for_message(count_type + " " + item_type) + "'");
                elements.back().row_bytes += unsigned(type_size(count_type));
            } else {
                if (!type_size(type)) return bad(n, "unknown property type '" + escape_for_message(type) + "'");
                elements.back().row_bytes += unsigned(type_size(type));
            }
        } else if (word != "comment" && word != "obj_info" && !word.empty()) {
            return bad(n, "unknown keyword '" + escape_for_message(word) + "'");
        }
    }
    if (!ended) return bad(n, "no end_header in the first " + std::to_string(head.size()) + " bytes");
    if (format.empty()) return bad(n, "no format line");
    const uint64_t body = *size - uint64_t(lines.tellg() < 0 ? head.size() : size_t(lines.tellg()));
    for (const Element& e : elements) {
        const unsigned long long row = format == "ascii" ? 2 : e.row_bytes;
        if (row > 0 && e.count > body / row)
            return bad(e.line, "declares " + std::to_string(e.count) + " rows, more than the " + std::to_string(body) +
                                   " bytes after the header can hold");
    }
    return ok_status();
}

}  // namespace body
