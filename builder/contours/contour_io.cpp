// Reading and writing `*.contours.json` with nlohmann-json.
#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "builder/contours/contour_stack.h"
#include "shared/atomic_file.h"

namespace body {
namespace {

using nlohmann::json;

// A string member, or `fallback` when absent; nullopt when present but not a string.
std::optional<std::string> string_member(const json& object, const char* key, const std::string& fallback) {
    auto it = object.find(key);
    if (it == object.end()) return fallback;
    if (!it->is_string()) return std::nullopt;
    return it->get<std::string>();
}

std::string place(const std::string& path, size_t slice) { return path + ": slice " + std::to_string(slice); }
std::string place(const std::string& path, size_t slice, size_t contour) {
    return place(path, slice) + " contour " + std::to_string(contour);
}

Result<Vec3> parse_color(const json& value, const std::string& where) {
    if (!value.is_array() || value.size() != 3) return input_error(where + ": color must be [r, g, b]");
    Vec3 c(0.0);
    for (int i = 0; i < 3; ++i) {
        if (!value[i].is_number()) return input_error(where + ": color must be [r, g, b] numbers");
        c[i] = value[i].get<double>();
        if (!(c[i] >= 0.0 && c[i] <= 1.0)) return input_error(where + ": color components must lie in [0, 1]");
    }
    return c;
}

Result<std::vector<StructureInfo>> parse_structures(const json& root, const std::string& path) {
    std::vector<StructureInfo> out;
    if (!root.contains("structures")) return out;
    const json& list = root["structures"];
    if (!list.is_array()) return input_error(path + ": \"structures\" must be an array");
    for (size_t i = 0; i < list.size(); ++i) {
        const std::string where = path + ": structure " + std::to_string(i);
        const json& s = list[i];
        if (!s.is_object() || !s.contains("id") || !s["id"].is_string())
            return input_error(where + ": needs a string \"id\"");
        StructureInfo info;
        info.id = s["id"].get<std::string>();
        if (info.id.empty()) return input_error(where + ": empty id");
        auto name = string_member(s, "name", info.id);
        if (!name) return input_error(where + ": \"name\" must be a string");
        info.name = *name;
        if (s.contains("color")) {
            auto c = parse_color(s["color"], where);
            if (!c) return c.error();
            info.color = *c;
        }
        for (const auto& other : out)
            if (other.id == info.id) return input_error(where + ": duplicate id '" + info.id + "'");
        out.push_back(std::move(info));
    }
    return out;
}

Result<Contour> parse_contour(const json& c, const std::string& path, size_t si, size_t ci,
                              const std::vector<StructureInfo>& structures) {
    const std::string where = place(path, si, ci);
    if (!c.is_object() || !c.contains("points") || !c["points"].is_array())
        return input_error(where + ": needs a \"points\" array");
    Contour contour;
    contour.source_slice = si;
    contour.source_contour = ci;
    const json& pts = c["points"];
    contour.points.reserve(pts.size());
    for (size_t k = 0; k < pts.size(); ++k) {
        const json& p = pts[k];
        if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
            return input_error(where + ": point " + std::to_string(k) + " must be [x, y]");
        Vec2 v(p[0].get<double>(), p[1].get<double>());
        if (!std::isfinite(v.x) || !std::isfinite(v.y))
            return input_error(where + ": point " + std::to_string(k) + " is not finite");
        contour.points.push_back(v);
    }
    if (c.contains("structure")) {
        if (!c["structure"].is_string()) return input_error(where + ": \"structure\" must be a string");
        contour.structure = c["structure"].get<std::string>();
        bool known = std::any_of(structures.begin(), structures.end(),
                                 [&](const StructureInfo& s) { return s.id == contour.structure; });
        if (!known) return input_error(where + ": unknown structure '" + contour.structure + "'");
    }
    return contour;
}

}  // namespace

Result<ContourStack> parse_contour_stack(const std::string& json_text, const std::string& path) {
    json root = json::parse(json_text, nullptr, /*allow_exceptions=*/false);
    if (root.is_discarded()) {
        // Re-parse with a SAX-free check to get the byte offset of the syntax error.
        try {
            json probe = json::parse(json_text);
            (void)probe;
        } catch (const json::parse_error& e) {
            return input_error(path + ": byte " + std::to_string(e.byte) + ": invalid JSON");
        } catch (const json::exception& e) {
            return input_error(path + ": invalid JSON (" + std::string(e.what()) + ")");
        }
        return input_error(path + ": invalid JSON");
    }
    if (!root.is_object() || string_member(root, "format", "") != std::optional<std::string>("bodygen.contours"))
        return input_error(path + ": not a contour stack (\"format\" must be \"bodygen.contours\")");
    if (!root.contains("version") || !root["version"].is_number_integer() || root["version"].get<int>() != 1)
        return input_error(path + ": unsupported version (expected 1)");
    ContourStack stack;
    auto units = string_member(root, "units", "mm");
    if (!units) return input_error(path + ": \"units\" must be a string");
    stack.units = *units;
    auto structures = parse_structures(root, path);
    if (!structures) return structures.error();
    stack.structures = std::move(*structures);

    if (!root.contains("slices") || !root["slices"].is_array()) return input_error(path + ": needs a \"slices\" array");
    const json& slices = root["slices"];
    std::vector<Slice> raw;
    for (size_t si = 0; si < slices.size(); ++si) {
        const json& s = slices[si];
        if (!s.is_object() || !s.contains("z") || !s["z"].is_number())
            return input_error(place(path, si) + ": needs a numeric \"z\"");
        Slice slice;
        slice.z = s["z"].get<double>();
        slice.source_index = si;
        if (!std::isfinite(slice.z)) return input_error(place(path, si) + ": z is not finite");
        if (!s.contains("contours") || !s["contours"].is_array())
            return input_error(place(path, si) + ": needs a \"contours\" array");
        const json& contours = s["contours"];
        for (size_t ci = 0; ci < contours.size(); ++ci) {
            auto c = parse_contour(contours[ci], path, si, ci, stack.structures);
            if (!c) return c.error();
            slice.contours.push_back(std::move(*c));
        }
        raw.push_back(std::move(slice));
    }
    std::stable_sort(raw.begin(), raw.end(), [](const Slice& a, const Slice& b) { return a.z < b.z; });
    for (Slice& s : raw) {
        if (!stack.slices.empty() && s.z - stack.slices.back().z < kSliceMergeTolerance) {
            auto& dst = stack.slices.back().contours;
            std::move(s.contours.begin(), s.contours.end(), std::back_inserter(dst));
        } else {
            stack.slices.push_back(std::move(s));
        }
    }
    return stack;
}

Result<ContourStack> read_contour_stack(const std::string& path) {
    auto text = read_file(path);
    if (!text) return text.error();
    return parse_contour_stack(*text, path);
}

std::string contour_stack_to_json(const ContourStack& stack) {
    json root;
    root["format"] = "bodygen.contours";
    root["version"] = 1;
    root["units"] = stack.units;
    json structures = json::array();
    for (const auto& s : stack.structures)
        structures.push_back({{"id", s.id}, {"name", s.name}, {"color", {s.color.r, s.color.g, s.color.b}}});
    root["structures"] = structures;
    json slices = json::array();
    for (const auto& slice : stack.slices) {
        json contours = json::array();
        for (const auto& c : slice.contours) {
            json pts = json::array();
            for (const Vec2& p : c.points) pts.push_back({p.x, p.y});
            json jc = {{"points", std::move(pts)}};
            if (!c.structure.empty()) jc["structure"] = c.structure;
            contours.push_back(std::move(jc));
        }
        slices.push_back({{"z", slice.z}, {"contours", std::move(contours)}});
    }
    root["slices"] = std::move(slices);
    return root.dump();
}

Status write_contour_stack(const std::string& path, const ContourStack& stack) {
    return write_file_atomically(path, [&](std::ostream& out) {
        out << contour_stack_to_json(stack) << '\n';
        return std::string();
    });
}

}  // namespace body
