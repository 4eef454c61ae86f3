// VRML97 meshes in (contract in vrml_reader.h). Two phases: parse the file into a
// generic node tree (any node type, fields kept by name; USE shares the DEF'd
// node), then walk the tree from the roots with the transform so far.
#include "builder/mesh_import/vrml_reader.h"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>

namespace body {
namespace {

constexpr int kMaxDepth = 64;  // nested nodes; deeper files are refused, never a stack overflow

struct Node;
using NodePtr = std::shared_ptr<const Node>;

struct Field {
    std::vector<double> numbers;  // numbers, and TRUE/FALSE as 1/0
    std::vector<NodePtr> nodes;   // SFNode / MFNode values (NULL is left out)
    size_t line = 0;              // where the value starts (for errors found later)
};

struct Node {
    std::string type, def;
    std::map<std::string, Field> fields;
};

struct Fail {
    size_t line;
    std::string reason;
};

class Parser {
public:
    explicit Parser(const std::string& text) : s_(text) {}

    // The top-level nodes; throws Fail.
    std::vector<NodePtr> parse_file() {
        std::vector<NodePtr> roots;
        for (std::string t = next(); !t.empty(); t = next()) {
            if (t == "ROUTE") {  // ROUTE a.b TO c.d: animation, nothing to draw
                for (int k = 0; k < 3; ++k)
                    if (next().empty()) throw Fail{line_, "unterminated ROUTE"};
                continue;
            }
            if (NodePtr n = node_from(t, 0)) roots.push_back(std::move(n));
        }
        return roots;
    }

private:
    static bool is_number(const std::string& t) {
        return !t.empty() &&
               (std::isdigit(static_cast<unsigned char>(t[0])) || t[0] == '-' || t[0] == '+' || t[0] == '.');
    }
    static bool is_word(const std::string& t) { return !t.empty() && !is_number(t) && !std::strchr("{}[]\"", t[0]); }

    void skip_space() {
        while (pos_ < s_.size()) {
            const char c = s_[pos_];
            if (c == '\n') ++line_;
            if (c == '#') {
                while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
            } else if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
                ++pos_;
            } else {
                return;
            }
        }
    }
    // The next token ("" at the end): a brace/bracket, a quoted string (its
    // content is not needed), or a run of other characters.
    std::string next() {
        if (!peeked_.empty()) return std::exchange(peeked_, std::string());
        skip_space();
        if (pos_ >= s_.size()) return {};
        const char c = s_[pos_];
        if (std::strchr("{}[]", c)) return std::string(1, s_[pos_++]);
        if (c == '"') {
            for (++pos_; pos_ < s_.size() && s_[pos_] != '"'; ++pos_) {
                if (s_[pos_] == '\\') ++pos_;
                if (pos_ < s_.size() && s_[pos_] == '\n') ++line_;
            }
            if (pos_ >= s_.size()) throw Fail{line_, "unterminated string"};
            ++pos_;
            return "\"";
        }
        const size_t start = pos_;
        while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_])) &&
               !std::strchr("{}[]\"#,", s_[pos_]))
            ++pos_;
        return s_.substr(start, pos_ - start);
    }
    const std::string& peek() {
        if (peeked_.empty()) peeked_ = next();
        return peeked_;
    }
    std::string expect_word(const std::string& what) {
        std::string t = next();
        if (t.empty()) throw Fail{line_, "unexpected end of file, expected " + what};
        if (!is_word(t)) throw Fail{line_, "expected " + what + ", found '" + t + "'"};
        return t;
    }

    // A node statement starting with token `t`: DEF name Type {...}, USE name, NULL.
    NodePtr node_from(std::string t, int depth) {
        if (depth > kMaxDepth) throw Fail{line_, "nodes nested deeper than " + std::to_string(kMaxDepth)};
        if (t == "NULL") return nullptr;
        if (t == "USE") {
            const std::string name = expect_word("a DEF name after USE");
            const auto it = defs_.find(name);
            if (it == defs_.end()) throw Fail{line_, "USE " + name + " before any DEF " + name};
            return it->second;
        }
        if (t == "PROTO" || t == "EXTERNPROTO") throw Fail{line_, t + " is not supported"};
        std::string def;
        if (t == "DEF") {
            def = expect_word("a name after DEF");
            t = expect_word("a node type after DEF " + def);
        }
        if (!is_word(t)) throw Fail{line_, "expected a node, found '" + t + "'"};
        auto node = std::make_shared<Node>();
        node->type = t;
        node->def = def;
        const size_t opened = line_;
        if (next() != "{") throw Fail{line_, "expected '{' after " + t};
        for (;;) {
            std::string f = next();
            if (f.empty()) throw Fail{opened, t + " node not closed before the end of the file"};
            if (f == "}") break;
            if (!is_word(f)) throw Fail{line_, "expected a field name in " + t + ", found '" + f + "'"};
            node->fields[f] = field_value(t + "." + f, depth, opened);
        }
        if (!def.empty()) defs_[def] = node;
        return node;
    }

    void value_into(Field& field, const std::string& t, const std::string& where, int depth) {
        if (is_number(t)) {
            char* end = nullptr;
            const double v = std::strtod(t.c_str(), &end);
            if (*end != '\0' || !std::isfinite(v)) throw Fail{line_, where + ": bad number '" + t + "'"};
            field.numbers.push_back(v);
        } else if (t == "TRUE" || t == "FALSE") {
            field.numbers.push_back(t == "TRUE" ? 1.0 : 0.0);
        } else if (t == "\"") {
            // strings (names, urls) carry nothing we draw
        } else if (is_word(t)) {
            if (NodePtr n = node_from(t, depth + 1)) field.nodes.push_back(std::move(n));
        } else {
            throw Fail{line_, where + ": unexpected '" + t + "'"};
        }
    }

    Field field_value(const std::string& where, int depth, size_t opened) {
        Field field;
        std::string t = next();
        field.line = line_;
        if (t.empty()) throw Fail{opened, where + ": node not closed before the end of the file"};
        if (t == "[") {
            const size_t list_opened = line_;
            for (t = next(); t != "]"; t = next()) {
                if (t.empty()) throw Fail{list_opened, where + ": '[' not closed before the end of the file"};
                value_into(field, t, where, depth);
            }
            return field;
        }
        if (is_number(t)) {  // SFVec3f, SFRotation, ...: the numbers that follow
            value_into(field, t, where, depth);
            while (is_number(peek())) value_into(field, next(), where, depth);
            return field;
        }
        value_into(field, t, where, depth);
        return field;
    }

    const std::string& s_;
    size_t pos_ = 0, line_ = 1;
    std::string peeked_;
    std::map<std::string, NodePtr> defs_;
};

const Field* field(const Node& n, const char* name) {
    const auto it = n.fields.find(name);
    return it == n.fields.end() ? nullptr : &it->second;
}

// numbers[0..k) of a field, else the default.
template <size_t K>
std::array<double, K> numbers(const Node& n, const char* name, std::array<double, K> fallback) {
    const Field* f = field(n, name);
    if (f && f->numbers.size() >= K)
        for (size_t k = 0; k < K; ++k) fallback[k] = f->numbers[k];
    return fallback;
}

const Node* first_node(const Node& n, const char* name) {
    const Field* f = field(n, name);
    return f && !f->nodes.empty() ? f->nodes[0].get() : nullptr;
}

// Axis-angle rotation as a 4x4 (Rodrigues); a zero axis is no rotation.
glm::dmat4 rotation(const std::array<double, 4>& r) {
    Vec3 a(r[0], r[1], r[2]);
    const double len = glm::length(a);
    if (len < 1e-12 || r[3] == 0.0) return glm::dmat4(1.0);
    a /= len;
    const double c = std::cos(r[3]), s = std::sin(r[3]), t = 1.0 - c;
    glm::dmat4 m(1.0);  // column-major: m[col][row]
    m[0] = {t * a.x * a.x + c, t * a.x * a.y + s * a.z, t * a.x * a.z - s * a.y, 0};
    m[1] = {t * a.x * a.y - s * a.z, t * a.y * a.y + c, t * a.y * a.z + s * a.x, 0};
    m[2] = {t * a.x * a.z + s * a.y, t * a.y * a.z - s * a.x, t * a.z * a.z + c, 0};
    return m;
}

glm::dmat4 translation(const std::array<double, 3>& t, double sign = 1.0) {
    glm::dmat4 m(1.0);
    m[3] = {sign * t[0], sign * t[1], sign * t[2], 1.0};
    return m;
}

// VRML97 6.52: T * C * R * SR * S * -SR * -C.
glm::dmat4 transform_of(const Node& n) {
    const auto c = numbers<3>(n, "center", {0, 0, 0});
    const auto sr = numbers<4>(n, "scaleOrientation", {0, 0, 1, 0});
    const auto s = numbers<3>(n, "scale", {1, 1, 1});
    glm::dmat4 scale(1.0);
    scale[0][0] = s[0], scale[1][1] = s[1], scale[2][2] = s[2];
    const glm::dmat4 srm = rotation(sr);
    return translation(numbers<3>(n, "translation", {0, 0, 0})) * translation(c) *
           rotation(numbers<4>(n, "rotation", {0, 0, 1, 0})) * srm * scale * glm::transpose(srm) * translation(c, -1.0);
}

struct Walk {
    const std::string& path;
    std::vector<Mesh> meshes;
    size_t visits = 0;
};

constexpr double kMetresToMm = 1000.0;
constexpr size_t kMaxVisits = size_t(1) << 20;  // USE of USE grows exponentially; refuse such files

void shape(const Node& n, const glm::dmat4& m, const std::string& name, Walk& w) {
    Mesh mesh;
    mesh.name = n.def.empty() ? name : n.def;
    if (const Node* app = first_node(n, "appearance"))
        if (const Node* mat = first_node(*app, "material")) {
            const auto d = numbers<3>(*mat, "diffuseColor", {0.8, 0.8, 0.8});
            mesh.color = Vec3(d[0], d[1], d[2]);
        }
    const Node* geo = first_node(n, "geometry");
    if (!geo || geo->type != "IndexedFaceSet") return;  // other geometry is not a mesh
    const Node* coord = first_node(*geo, "coord");
    const Field* point = coord ? field(*coord, "point") : nullptr;
    const Field* index = field(*geo, "coordIndex");
    if (!point || !index) return;
    const size_t count = point->numbers.size() / 3;
    for (size_t v = 0; v < count; ++v) {
        const glm::dvec4 p =
            m * glm::dvec4(point->numbers[v * 3], point->numbers[v * 3 + 1], point->numbers[v * 3 + 2], 1);
        mesh.positions.emplace_back(p.x * kMetresToMm, p.y * kMetresToMm, p.z * kMetresToMm);
    }
    // A mirroring transform turns counter-clockwise faces clockwise; so does ccw FALSE.
    const bool flip = (glm::determinant(glm::dmat3(m)) < 0) != (numbers<1>(*geo, "ccw", {1})[0] == 0.0);
    std::vector<uint32_t> polygon;
    auto close = [&] {
        for (size_t k = 1; k + 1 < polygon.size(); ++k) {
            const uint32_t a = polygon[0], b = polygon[k], c = polygon[k + 1];
            mesh.indices.insert(mesh.indices.end(), {a, flip ? c : b, flip ? b : c});
        }
        polygon.clear();
    };
    for (double i : index->numbers) {
        if (i < 0) {
            close();
            continue;
        }
        if (i != std::floor(i) || i >= double(count)) {
            char why[128];
            std::snprintf(why, sizeof why, "coordIndex %.17g out of range (%zu points)", i, count);
            throw Fail{index->line, mesh.name + ": " + why};
        }
        polygon.push_back(uint32_t(i));
    }
    close();
    if (mesh.triangle_count() > 0) w.meshes.push_back(std::move(mesh));
}

void walk(const Node& n, const glm::dmat4& parent, const std::string& name, int depth, Walk& w) {
    if (++w.visits > kMaxVisits)
        throw Fail{0, "more than " + std::to_string(kMaxVisits) + " node instances (USE repeats)"};
    if (depth > kMaxDepth) throw Fail{0, "nodes nested deeper than " + std::to_string(kMaxDepth)};
    const std::string here = n.def.empty() ? name : n.def;
    if (n.type == "Shape") return shape(n, parent, name, w);
    const glm::dmat4 m = n.type == "Transform" ? parent * transform_of(n) : parent;
    std::vector<NodePtr> kids;
    if (const Field* f = field(n, "children")) kids = f->nodes;
    if (const Field* f = field(n, "level"); f && !f->nodes.empty()) kids.push_back(f->nodes[0]);
    if (const Field* f = field(n, "choice")) {
        const double which = numbers<1>(n, "whichChoice", {-1})[0];
        if (which >= 0 && which < double(f->nodes.size())) kids.push_back(f->nodes[size_t(which)]);
    }
    for (const NodePtr& k : kids) walk(*k, m, here, depth + 1, w);
}

}  // namespace

Result<std::vector<Mesh>> read_vrml(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return input_error(path + ": cannot open");
    std::stringstream buf;
    buf << in.rdbuf();
    const std::string text = buf.str();
    const std::string magic = "#VRML V2.0 utf8";
    if (text.compare(0, magic.size(), magic) != 0)
        return input_error(path + ":1: not VRML97 (the file must start with \"" + magic + "\")");
    Walk w{path, {}, 0};
    try {
        Parser parser(text);
        const auto roots = parser.parse_file();
        const std::string stem = std::filesystem::path(path).stem().string();
        for (const NodePtr& r : roots) walk(*r, glm::dmat4(1.0), stem, 0, w);
    } catch (const Fail& f) {
        std::string where = path;
        if (f.line) where.append(":").append(std::to_string(f.line));
        return input_error(where.append(": ").append(f.reason));
    }
    if (w.meshes.empty()) return input_error(path + ": no IndexedFaceSet with triangles");
    std::map<std::string, int> seen;
    for (Mesh& m : w.meshes)
        if (int k = ++seen[m.name]; k > 1) m.name.append("_").append(std::to_string(k));
    return std::move(w.meshes);
}

}  // namespace body
