#include "shared/obj_io.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <ostream>
#include <string_view>
#include <thread>

#include "shared/atomic_file.h"
#include "shared/input_file.h"

namespace body {
namespace {

// The exact spelling printf's %.Ng gives `value` (N = precision), without
// libstdc++'s to_chars with a precision (its slow path): the value times the
// power of ten that leaves N digits before the point, one correctly rounded
// product of two doubles (powers up to 1e22 are exact), is within 0.5 ulp of
// the exact scaled value, under 1e-7 for N <= 9; rounded to the nearest
// integer it gives the N digits unless its fraction lies within 1e-6 of a
// half. Those values, zero, subnormals, magnitudes outside 1e-14..1e30 and
// precisions over 9 take to_chars with the precision itself.
char* general_digits(char* first, char* last, double value, int precision) {
    static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                        1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    const auto slow = [&] { return std::to_chars(first, last, value, std::chars_format::general, precision).ptr; };
    const double magnitude = std::fabs(value);
    if (!std::isnormal(value) || precision > 9 || magnitude < 1e-14 || magnitude >= 1e30) return slow();
    int exponent = int(std::floor(std::log10(magnitude)));  // may be off by one at a power of ten: checked below
    const int shift = precision - 1 - exponent;
    if (shift > 22 || shift < -22) return slow();
    const double scaled = shift >= 0 ? magnitude * kPow10[shift] : magnitude / kPow10[-shift];
    const double low = kPow10[precision - 1], high = kPow10[precision];
    if (scaled < low || scaled >= high) return slow();
    const double whole = std::floor(scaled), fraction = scaled - whole;
    if (std::fabs(fraction - 0.5) < 1e-6) return slow();
    uint64_t mantissa = uint64_t(whole) + (fraction > 0.5 ? 1 : 0);
    if (mantissa == uint64_t(high)) {  // 9.99..95 rounded up to 10.0..0
        mantissa = uint64_t(low);
        ++exponent;
    }
    char digits[20] = {};
    int count = precision;
    for (int i = count - 1; i >= 0; --i) {
        digits[i] = char('0' + mantissa % 10);
        mantissa /= 10;
    }
    const bool negative = value < 0;
    while (count > 1 && digits[count - 1] == '0') --count;
    char* out = first;
    if (negative) *out++ = '-';
    if (exponent < -4 || exponent >= precision) {
        *out++ = digits[0];
        if (count > 1) {
            *out++ = '.';
            for (int i = 1; i < count; ++i) *out++ = digits[i];
        }
        *out++ = 'e';
        *out++ = exponent < 0 ? '-' : '+';
        const int power = std::abs(exponent);
        if (power < 10) *out++ = '0';
        return std::to_chars(out, last, power).ptr;
    }
    if (exponent < 0) {
        *out++ = '0';
        *out++ = '.';
        for (int i = 0; i < -exponent - 1; ++i) *out++ = '0';
        for (int i = 0; i < count; ++i) *out++ = digits[i];
        return out;
    }
    for (int i = 0; i <= exponent; ++i) *out++ = i < count ? digits[i] : '0';
    if (count > exponent + 1) {
        *out++ = '.';
        for (int i = exponent + 1; i < count; ++i) *out++ = digits[i];
    }
    return out;
}

// Rows are gathered into `rows` and written a megabyte at a time: one stream
// call per row (its sentry, a copy into the file buffer, a system call every
// 8 KB) was most of the writing's own time.
constexpr size_t kChunk = 1 << 20;
void flush_if_full(std::ostream& out, std::string& rows, bool always = false) {
    if (rows.size() < kChunk && !always) return;
    out.write(rows.data(), std::streamsize(rows.size()));
    rows.clear();
}

// Each row is spelled into a local buffer and appended once: appending each
// number and space to the string cost more than the integers' digits.
void write_row(std::string& rows, const char* tag, const Vec3& p, int precision) {
    char line[3 * 48 + 8];
    char* end = line;
    while (*tag != '\0') *end++ = *tag++;
    for (int k = 0; k < 3; ++k) {
        *end++ = ' ';
        end = general_digits(end, line + sizeof(line), p[k], precision);
    }
    *end++ = '\n';
    rows.append(line, end);
}

// A face row, 1-based vertex numbers from `base`.
void write_face(std::string& rows, const uint32_t* tri, size_t base, bool normals) {
    char line[3 * 48 + 8];
    char* end = line;
    *end++ = 'f';
    for (int k = 0; k < 3; ++k) {
        const size_t i = base + tri[k];
        *end++ = ' ';
        end = std::to_chars(end, end + 20, i).ptr;
        if (normals) {
            *end++ = '/';
            *end++ = '/';
            end = std::to_chars(end, end + 20, i).ptr;
        }
    }
    *end++ = '\n';
    rows.append(line, end);
}

// Rows 0..count-1 spelled by row(i, text) and written in order. With
// `threads` > 1, blocks of kBlock rows are spelled on that many threads at a
// time and written in order when all are done (the same bytes; memory for
// `threads` blocks of text).
constexpr size_t kBlock = 1 << 15;
template <class Row>
void write_rows(std::ostream& out, std::string& rows, size_t count, unsigned threads, Row&& row) {
    if (threads <= 1 || count < 2 * kBlock) {
        for (size_t i = 0; i < count; ++i) {
            row(i, rows);
            flush_if_full(out, rows);
        }
        return;
    }
    flush_if_full(out, rows, true);
    std::vector<std::string> parts(threads);
    for (size_t first = 0; first < count; first += threads * kBlock) {
        auto spell = [&](size_t w) {
            parts[w].clear();
            const size_t begin = std::min(count, first + w * kBlock), end = std::min(count, begin + kBlock);
            for (size_t i = begin; i < end; ++i) row(i, parts[w]);
        };
        std::vector<std::thread> pool;
        for (size_t w = 1; w < threads; ++w) pool.emplace_back(spell, w);
        spell(0);
        for (auto& t : pool) t.join();
        for (const std::string& part : parts) out.write(part.data(), std::streamsize(part.size()));
    }
}

std::string write_meshes(std::ostream& out, std::span<const Mesh> meshes, const ObjWriteOptions& options) {
    out.precision(options.precision);
    out << "# bodygen OBJ\n";
    size_t base = 1;
    const int precision = std::clamp(options.precision, 1, 17);
    std::string rows;
    rows.reserve(kChunk + 256);
    for (const Mesh& mesh : meshes) {
        rows.append("o ").append(mesh.name.empty() ? std::string("structure") : mesh.name).append("\n");
        write_rows(out, rows, mesh.positions.size(), options.threads,
                   [&](size_t i, std::string& text) { write_row(text, "v", mesh.positions[i], precision); });
        std::vector<Vec3> computed;
        std::span<const Vec3> normals = mesh.normals;
        if (options.normals && normals.size() != mesh.positions.size()) {
            computed = vertex_normals(mesh.positions, mesh.indices);
            normals = computed;
        }
        if (options.normals)
            write_rows(out, rows, normals.size(), options.threads,
                       [&](size_t i, std::string& text) { write_row(text, "vn", normals[i], precision); });
        write_rows(out, rows, mesh.indices.size() / 3, options.threads,
                   [&](size_t t, std::string& text) { write_face(text, &mesh.indices[3 * t], base, options.normals); });
        base += mesh.positions.size();
    }
    flush_if_full(out, rows, true);
    return {};
}

// 'word', escaped (built by append: GCC 12's -Wrestrict misfires on "'" + s).
std::string in_quotes(std::string_view word) {
    std::string out = "'";
    return out.append(escape_for_message(word, 40)).append("'");
}

// Why `word` is not a finite float ("" when it is one).
std::string number_fault(std::string_view word) {
    const std::string number(word);
    char* stop = nullptr;
    const double v = std::strtod(number.c_str(), &stop);
    if (stop == number.c_str() || *stop != '\0') return in_quotes(number) + " is not a number";
    if (!std::isfinite(v) || std::fabs(v) > 3.0e38) return in_quotes(number) + " is not a finite float";
    return {};
}

// Why face corner `ref` (v, v/t, v//n or v/t/n, 1-based or negative) does not
// name defined vertices, texture coordinates and normals ("" when it does).
std::string corner_fault(std::string_view ref, const size_t (&defined)[3]) {
    static const char* kWhat[3] = {"vertex", "texture coordinate", "normal"};
    static const char* kPlural[3] = {"vertices", "texture coordinates", "normals"};
    if (std::count(ref.begin(), ref.end(), '/') > 2) return "has more than 3 parts (v/t/n)";
    size_t part = 0;
    for (size_t start = 0; start <= ref.size(); ++part) {
        size_t slash = ref.find('/', start);
        if (slash == std::string_view::npos) slash = ref.size();
        const std::string index(ref.substr(start, slash - start));
        start = slash + 1;
        if (index.empty() && part == 1 && slash < ref.size()) continue;  // v//n
        char* stop = nullptr;
        errno = 0;
        const long long i = std::strtoll(index.c_str(), &stop, 10);
        if (stop == index.c_str() || *stop != '\0' || errno == ERANGE) return "is not an index";
        const unsigned long long magnitude =
            i < 0 ? 0ull - static_cast<unsigned long long>(i) : static_cast<unsigned long long>(i);
        if (i == 0 || magnitude > defined[part])
            return std::string(kWhat[part]) + " index " + index + " is outside 1.." + std::to_string(defined[part]) +
                   " (the " + kPlural[part] + " defined so far)";
    }
    return {};
}

// The common spellings, checked in place: a plain decimal number ([+-]digits[.digits]
// [e[+-]digits], at least one digit) below 1e38 (integer digits + exponent <= 38).
// True only where number_fault would find nothing; anything else goes to it (the
// check was half of reading a large OBJ: a string and a strtod per number).
bool plain_number(std::string_view w) {
    size_t i = 0, digits = 0, int_digits = 0;
    if (i < w.size() && (w[i] == '+' || w[i] == '-')) ++i;
    bool leading = true;  // integer digits after leading zeros
    for (; i < w.size() && w[i] >= '0' && w[i] <= '9'; ++i, ++digits) {
        leading = leading && w[i] == '0';
        int_digits += !leading;
    }
    if (i < w.size() && w[i] == '.')
        for (++i; i < w.size() && w[i] >= '0' && w[i] <= '9'; ++i) ++digits;
    if (digits == 0) return false;
    int exponent = 0;
    if (i < w.size() && (w[i] == 'e' || w[i] == 'E')) {
        ++i;
        const bool negative = i < w.size() && w[i] == '-';
        if (i < w.size() && (w[i] == '+' || w[i] == '-')) ++i;
        size_t e_digits = 0;
        for (; i < w.size() && w[i] >= '0' && w[i] <= '9' && e_digits < 4; ++i, ++e_digits)
            exponent = exponent * 10 + (w[i] - '0');
        if (e_digits == 0) return false;
        if (negative) exponent = -exponent;
    }
    return i == w.size() && int(int_digits) + exponent <= 38;
}

// The same for a face corner: v, v/t, v//n or v/t/n with each index a plain
// [-]digits (up to 18) naming a defined element. True only where corner_fault
// would find nothing.
bool plain_corner(std::string_view ref, const size_t (&defined)[3]) {
    size_t part = 0, i = 0;
    for (;; ++part) {
        if (part > 2) return false;
        const bool negative = i < ref.size() && ref[i] == '-';
        i += negative;
        size_t digits = 0;
        unsigned long long value = 0;
        for (; i < ref.size() && ref[i] >= '0' && ref[i] <= '9' && digits < 18; ++i, ++digits)
            value = value * 10 + unsigned(ref[i] - '0');
        if (digits == 0) {
            // Only v//n: an empty texture part followed by a slash.
            if (negative || part != 1 || i >= ref.size() || ref[i] != '/') return false;
        } else if (value == 0 || value > defined[part]) {
            return false;
        }
        if (i == ref.size()) return true;
        if (ref[i] != '/') return false;
        ++i;
    }
}

// tinyobjloader reads "nan", "one" or a missing coordinate as 0, keeps any
// face index (texture and normal indices too) and drops 2-vertex faces; this
// pass refuses those first, naming the line: "PATH: line N: reason".
// v takes x y z, x y z w or x y z r g b; vt 1 to 3 numbers; vn 3.
Status check_obj_text(const std::string& text, const std::string& path) {
    size_t defined[3] = {0, 0, 0};  // v, vt, vn so far
    size_t line_no = 0, pos = 0;
    auto fail = [&](const std::string& why) {
        return input_error(path + ": line " + std::to_string(line_no) + ": " + why);
    };
    std::vector<std::string_view> tok;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string::npos) end = text.size();
        std::string_view line(text.data() + pos, end - pos);
        pos = end + 1;
        ++line_no;
        if (line.find('\0') != std::string_view::npos) return fail("NUL byte (not a text file)");
        if (const size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
        split_words(line, tok);
        if (tok.empty()) continue;
        const size_t values = tok.size() - 1;
        const int kind = tok[0] == "v" ? 0 : tok[0] == "vt" ? 1 : tok[0] == "vn" ? 2 : -1;
        if (kind == 0 && values < 3) return fail("vertex needs x y z, got " + std::to_string(values) + " values");
        if (kind == 0 && values != 3 && values != 4 && values != 6)
            return fail("vertex has " + std::to_string(values) + " values (x y z, x y z w or x y z r g b)");
        if (kind == 1 && (values < 1 || values > 3))
            return fail("texture coordinate has " + std::to_string(values) + " values (1 to 3)");
        if (kind == 2 && values != 3) return fail("normal has " + std::to_string(values) + " values (x y z)");
        if (kind >= 0) {
            static const char* kWhat[3] = {"vertex coordinate ", "texture coordinate ", "normal coordinate "};
            for (size_t k = 1; k < tok.size(); ++k)
                if (!plain_number(tok[k]))
                    if (std::string why = number_fault(tok[k]); !why.empty()) return fail(kWhat[kind] + why);
            ++defined[kind];
        } else if (tok[0] == "f") {
            if (values < 3) return fail("face has " + std::to_string(values) + " vertices, at least 3 needed");
            for (size_t k = 1; k < tok.size(); ++k)
                if (!plain_corner(tok[k], defined))
                    if (std::string why = corner_fault(tok[k], defined); !why.empty())
                        return fail(why.find(" index ") != std::string::npos
                                        ? "face " + why
                                        : "face vertex " + in_quotes(tok[k]) + " " + why);
        }
    }
    return ok_status();
}

}  // namespace

Status write_obj(const std::string& path, std::span<const Mesh> meshes, const ObjWriteOptions& options) {
    return write_file_atomically(path, [&](std::ostream& out) { return write_meshes(out, meshes, options); });
}

Result<std::vector<Mesh>> read_obj(const std::string& path) {
    auto text = read_file(path);  // checks for a regular file first
    if (!text) return text.error();
    return parse_obj(*text, path);
}

Result<std::vector<Mesh>> parse_obj(const std::string& text, const std::string& path) {
    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    if (Status valid = check_obj_text(text, path); !valid) return valid.error();
    tinyobj::ObjReader reader;
    if (!reader.ParseFromString(text, "", config)) {
        std::string why = reader.Error();
        while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
        for (char& c : why)
            if (c == '\n') c = ' ';
        return input_error(path + ": not a readable OBJ file: " + (why.empty() ? "parse error" : why));
    }
    const auto& attrib = reader.GetAttrib();
    const size_t vertex_total = attrib.vertices.size() / 3;
    std::vector<Mesh> meshes;
    // File vertex -> this object's vertex (kUnset: not yet used by it); one array for
    // all objects, the entries an object set cleared after it.
    constexpr uint32_t kUnset = UINT32_MAX;
    std::vector<uint32_t> remap(vertex_total, kUnset);
    for (const auto& shape : reader.GetShapes()) {
        Mesh mesh;
        // Unnamed objects (plain scanner/CAD exports) are named after the file.
        mesh.name = shape.name.empty() ? std::filesystem::path(path).stem().string() : shape.name;
        mesh.indices.reserve(shape.mesh.indices.size());
        for (const auto& idx : shape.mesh.indices) {
            if (idx.vertex_index < 0 || size_t(idx.vertex_index) >= vertex_total)
                return input_error(path + ": object '" + shape.name + "': vertex index out of range");
            uint32_t& at = remap[size_t(idx.vertex_index)];
            if (at == kUnset) {
                const float* v = &attrib.vertices[3 * size_t(idx.vertex_index)];
                Vec3 p(v[0], v[1], v[2]);
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                    return input_error(path + ": object '" + shape.name + "': non-finite vertex");
                at = uint32_t(mesh.positions.size());
                mesh.positions.push_back(p);
            }
            mesh.indices.push_back(at);
        }
        for (const auto& idx : shape.mesh.indices) remap[size_t(idx.vertex_index)] = kUnset;
        if (!mesh.indices.empty()) meshes.push_back(std::move(mesh));
    }
    if (meshes.empty()) return input_error(path + ": no triangles");
    return meshes;
}

Result<Mesh> read_obj_merged(const std::string& path) {
    auto meshes = read_obj(path);
    if (!meshes) return meshes.error();
    Mesh merged;
    merged.name = meshes->size() == 1 ? meshes->front().name : std::filesystem::path(path).stem().string();
    std::map<std::tuple<double, double, double>, uint32_t> weld;
    for (const Mesh& m : *meshes) {
        std::vector<uint32_t> remap(m.positions.size());
        for (size_t i = 0; i < m.positions.size(); ++i) {
            const Vec3& p = m.positions[i];
            auto [it, inserted] = weld.emplace(std::make_tuple(p.x, p.y, p.z), uint32_t(merged.positions.size()));
            if (inserted) merged.positions.push_back(p);
            remap[i] = it->second;
        }
        for (uint32_t i : m.indices) merged.indices.push_back(remap[i]);
    }
    return merged;
}

}  // namespace body
