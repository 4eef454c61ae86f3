// The "links" section of contour stack files (contract in contour_links.h).
#include "builder/contours/contour_links.h"

#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

namespace body {
namespace {

using nlohmann::json;

constexpr const char* kShape =
    R"(must be {"cut": [A, B]}, {"join": [A, B]} or {"exclude": A} with A, B = [slice, contour])";

std::optional<ContourRef> to_ref(const json& v) {
    if (!v.is_array() || v.size() != 2 || !v[0].is_number_unsigned() || !v[1].is_number_unsigned()) return {};
    return ContourRef{v[0].get<size_t>(), v[1].get<size_t>()};
}

std::string describe(const ContourRef& r) {
    return "slice " + std::to_string(r.slice) + " contour " + std::to_string(r.contour);
}

std::string number(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

// Index of every contour by its file reference (first wins after a repair split).
std::map<ContourRef, ContourPlace> index_contours(const ContourStack& stack) {
    std::map<ContourRef, ContourPlace> out;
    for (size_t s = 0; s < stack.slices.size(); ++s)
        for (size_t k = 0; k < stack.slices[s].contours.size(); ++k) {
            const Contour& c = stack.slices[s].contours[k];
            out.emplace(ContourRef{c.source_slice, c.source_contour}, ContourPlace{s, k});
        }
    return out;
}

}  // namespace

Result<std::vector<LinkOverride>> parse_link_overrides(const json& links, const std::string& path) {
    if (!links.is_array()) return input_error(path + ": \"links\" must be an array");
    std::vector<LinkOverride> out;
    for (size_t i = 0; i < links.size(); ++i) {
        const json& e = links[i];
        const std::string where = path + ": links entry " + std::to_string(i) + ": ";
        LinkOverride o;
        int kinds = 0;
        bool ok = e.is_object();
        if (ok) {
            for (const auto& [name, edit] : {std::pair{"cut", LinkEdit::Cut}, std::pair{"join", LinkEdit::Join}}) {
                auto it = e.find(name);
                if (it == e.end()) continue;
                ++kinds, o.edit = edit;
                const bool pair = it->is_array() && it->size() == 2;
                auto a = pair ? to_ref((*it)[0]) : std::nullopt, b = pair ? to_ref((*it)[1]) : std::nullopt;
                ok = ok && a && b;
                if (a && b) o.a = *a, o.b = *b;
            }
            if (auto it = e.find("exclude"); it != e.end()) {
                ++kinds, o.edit = LinkEdit::Exclude;
                auto a = to_ref(*it);
                ok = ok && a;
                if (a) o.a = *a;
            }
        }
        if (!ok || kinds != 1) return input_error(where + kShape);
        out.push_back(o);
    }
    return out;
}

std::optional<ContourPlace> find_contour(const ContourStack& stack, const ContourRef& ref) {
    for (size_t s = 0; s < stack.slices.size(); ++s)
        for (size_t k = 0; k < stack.slices[s].contours.size(); ++k)
            if (names(ref, stack.slices[s].contours[k])) return ContourPlace{s, k};
    return std::nullopt;
}

Status check_link_overrides(const ContourStack& stack, const std::string& path) {
    if (stack.links.empty()) return ok_status();
    const auto index = index_contours(stack);
    for (size_t i = 0; i < stack.links.size(); ++i) {
        const LinkOverride& o = stack.links[i];
        const std::string where = path + ": links entry " + std::to_string(i) + ": ";
        auto a = index.find(o.a), b = index.find(o.b);
        if (a == index.end()) return input_error(where + describe(o.a) + ": no such contour");
        if (o.edit == LinkEdit::Exclude) continue;
        if (b == index.end()) return input_error(where + describe(o.b) + ": no such contour");
        const size_t sa = a->second.slice, sb = b->second.slice;
        if (sa + 1 != sb && sb + 1 != sa)
            return input_error(where + describe(o.a) + " and " + describe(o.b) + " are not on adjacent slices (z = " +
                               number(stack.slices[sa].z) + " and " + number(stack.slices[sb].z) + ")");
        const std::string& la = stack.slices[sa].contours[a->second.position].structure;
        const std::string& lb = stack.slices[sb].contours[b->second.position].structure;
        if (o.edit == LinkEdit::Join && la != lb)
            return input_error(where + "join of contours of different structures ('" + la + "' and '" + lb + "')");
    }
    return ok_status();
}

json link_overrides_to_json(const ContourStack& stack) {
    const auto index = index_contours(stack);
    json out = json::array();
    for (const LinkOverride& o : stack.links) {
        auto a = index.find(o.a), b = index.find(o.b);
        if (a == index.end() || (o.edit != LinkEdit::Exclude && b == index.end())) continue;
        const json ja = {a->second.slice, a->second.position};
        if (o.edit == LinkEdit::Exclude)
            out.push_back({{"exclude", ja}});
        else
            out.push_back(
                {{o.edit == LinkEdit::Cut ? "cut" : "join", {ja, json{b->second.slice, b->second.position}}}});
    }
    return out;
}

}  // namespace body
