// Exhibit stages: sources -> parts -> progressive meshes (threads) -> scene manifest.
#include "builder/exhibit/exhibit.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <map>
#include <mutex>
#include <set>
#include <thread>

#include "builder/exhibit/names.h"
#include "builder/exhibit/palette.h"
#include "builder/lod/bpm_writer.h"

namespace body::exhibit {
namespace {

// ------------------------------------------------------------ parts

ContourStack one_structure(const ContourStack& stack, const StructureInfo& s) {
    ContourStack part;
    part.units = stack.units;
    part.ras_axes = stack.ras_axes;
    part.voxel = stack.voxel;
    part.structures = {s};
    size_t first = SIZE_MAX, last = 0;
    std::vector<Slice> slices;
    for (const Slice& slice : stack.slices) {
        Slice mine{slice.z, {}, slice.source_index};
        for (const Contour& c : slice.contours)
            if (c.structure == s.id) mine.contours.push_back(c);
        if (!mine.contours.empty()) first = std::min(first, slices.size()), last = slices.size();
        slices.push_back(std::move(mine));
    }
    if (first != SIZE_MAX) part.slices.assign(slices.begin() + long(first), slices.begin() + long(last) + 1);
    return part;
}

// ------------------------------------------------------------ one part

// Mirrors data axis k (positions, normals, winding) so a left-handed frame becomes proper.
void mirror(Mesh& mesh, int k) {
    for (Vec3& p : mesh.positions) p[k] = -p[k];
    for (Vec3& n : mesh.normals) n[k] = -n[k];
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
}

std::array<Vec3, 3> proper_axes(std::array<Vec3, 3> axes) {
    const int k = mirror_axis(axes);
    if (k >= 0) axes[size_t(k)] = -axes[size_t(k)];
    return axes;
}

BuiltPart build_one(const Part& part, const PartOptions& options) {
    BuiltPart out;
    const auto start = std::chrono::steady_clock::now();
    Mesh mesh;
    if (part.contours) {
        BuildOptions build = options.build;
        build.jobs = 1;
        build.progress = nullptr;
        build.warning = [&out](const std::string& w) { out.warnings.push_back(w); };
        auto built = build_structures(*part.contours, build, part.source);
        if (!built) {
            out.error = built.error();
            return out;
        }
        if (built->empty()) {
            out.error = input_error(part.source + ": " + part.name + ": no contours");
            return out;
        }
        mesh = std::move(built->front().mesh);
        out.closed_manifold = built->front().closed_manifold;
    } else if (part.mesh) {
        mesh = *part.mesh;
        out.closed_manifold = analyze_topology(mesh.positions, mesh.indices).closed_manifold();
    }
    if (mesh.triangle_count() == 0) {
        out.error = input_error(part.source + ": " + part.name + ": no triangles");
        return out;
    }
    mesh.name = part.name;
    if (const int k = mirror_axis(part.ras_axes); k >= 0) mirror(mesh, k);
    lod::LodOptions lod = options.lod;
    lod.threads = 1;  // parallel across parts instead
    auto bytes = lod::encode_bpm(std::span<const Mesh>(&mesh, 1), lod);
    if (!bytes) {
        out.error = bytes.error();
        return out;
    }
    out.bpm = std::move(*bytes);
    out.triangles = mesh.triangle_count();
    const auto m = kiosk_rotation(proper_axes(part.ras_axes));
    out.lo = Vec3(1e300), out.hi = Vec3(-1e300);
    for (const Vec3& p : mesh.positions) {
        Vec3 q;
        for (int r = 0; r < 3; ++r) q[r] = m[size_t(r)][0] * p.x + m[size_t(r)][1] * p.y + m[size_t(r)][2] * p.z;
        out.lo = glm::min(out.lo, q), out.hi = glm::max(out.hi, q);
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return out;
}

std::string readable_group(const std::string& group) {
    std::string s = group;
    for (char& c : s)
        if (c == '-' || c == '_') c = ' ';
    if (!s.empty()) s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
    return s;
}

}  // namespace

std::vector<Part> parts_from_stack(const ContourStack& stack, const std::string& source,
                                   const std::array<Vec3, 3>& fallback_axes) {
    std::vector<Part> parts;
    for (const StructureInfo& s : stack.structures) {
        Part p;
        p.name = s.name.empty() ? s.id : s.name;
        p.source = source;
        // The format's default grey is no colour; black is a display table's "unset"
        // (MRIcron .lut files leave labels black) and cannot be shaded on a kiosk.
        if (s.color != Vec3(0.8, 0.8, 0.8) && s.color != Vec3(0.0)) p.colour = s.color;
        p.ras_axes = stack.ras_axes.value_or(fallback_axes);
        p.contours = one_structure(stack, s);
        parts.push_back(std::move(p));
    }
    return parts;
}

std::vector<Part> parts_from_meshes(std::vector<Mesh> meshes, const std::string& source,
                                    const std::array<Vec3, 3>& axes) {
    std::vector<Part> parts;
    for (Mesh& m : meshes) {
        Part p;
        p.name = m.name.empty() ? "mesh " + std::to_string(parts.size() + 1) : m.name;
        p.source = source;
        p.ras_axes = axes;
        // Mesh readers leave the default grey where the file has no colour (OBJ, STL, ...);
        // VRML's diffuseColor comes through. Black stays unset, as for stacks.
        if (m.color != Vec3(0.8, 0.8, 0.8) && m.color != Vec3(0.0)) p.colour = m.color;
        p.mesh = std::move(m);
        parts.push_back(std::move(p));
    }
    return parts;
}

std::vector<BuiltPart> build_parts(const std::vector<Part>& parts, const PartOptions& options) {
    std::vector<BuiltPart> out(parts.size());
    std::atomic<size_t> next{0};
    size_t done = 0;
    std::mutex mutex;
    auto work = [&] {
        for (size_t i; (i = next.fetch_add(1)) < parts.size();) {
            out[i] = build_one(parts[i], options);
            std::lock_guard lock(mutex);
            ++done;
            if (options.progress) options.progress(done, parts.size());
        }
    };
    const unsigned n = std::max(1u, std::min<unsigned>(options.jobs, unsigned(parts.size())));
    std::vector<std::thread> threads;
    for (unsigned t = 1; t < n; ++t) threads.emplace_back(work);
    work();
    for (std::thread& t : threads) t.join();
    return out;
}

std::vector<std::string> model_stems(const std::vector<Part>& parts) {
    std::vector<std::string> stems;
    std::set<std::string> used;
    for (const Part& p : parts) {
        std::string stem = p.name;
        for (char& c : stem)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
        while (!stem.empty() && stem[0] == '.') stem.erase(0, 1);
        if (stem.empty()) stem = "structure";
        std::string unique = stem;
        for (int k = 2; used.count(unique); ++k) unique = stem + "_" + std::to_string(k);
        used.insert(unique);
        stems.push_back(unique);
    }
    return stems;
}

// The input slices of the kept contour-built parts in the kiosk's world
// (scene.json cut_plane.slices, where the kiosk's cut plane snaps): each
// stack's planes z = c that hold a contour of the part, mirrored and turned as
// its model is, so the plane is dot(M e_z, p) = +-c. One normal per scene: the
// first such part's, and the parts whose slices share it.
void add_slices(const std::vector<Part>& parts, const std::vector<size_t>& kept, nlohmann::json& scene) {
    std::optional<Vec3> normal;
    std::vector<double> at;
    for (size_t i : kept) {
        const Part& p = parts[i];
        if (!p.contours) continue;
        const auto m = kiosk_rotation(proper_axes(p.ras_axes));
        const Vec3 n(m[0][2], m[1][2], m[2][2]);
        const double sign = mirror_axis(p.ras_axes) == 2 ? -1.0 : 1.0;
        if (!normal) normal = n;
        if (glm::length(n - *normal) > 1e-9) continue;
        for (const Slice& s : p.contours->slices)
            if (!s.contours.empty()) at.push_back(sign * s.z + 0.0);  // + 0.0: no -0 in the file
    }
    std::sort(at.begin(), at.end());
    at.erase(std::unique(at.begin(), at.end()), at.end());
    if (!normal || at.empty() || at.size() > 100000) return;
    scene["cut_plane"] = {{"slices", at}, {"slice_normal", {normal->x + 0.0, normal->y + 0.0, normal->z + 0.0}}};
}

nlohmann::json scene_for(const std::vector<Part>& parts, const std::vector<BuiltPart>& built,
                         const std::vector<std::string>& files, const SceneOptions& options) {
    std::vector<size_t> kept;
    for (size_t i = 0; i < parts.size(); ++i)
        if (!built[i].bpm.empty() && !files[i].empty()) kept.push_back(i);
    std::vector<Box> boxes;
    std::vector<std::optional<Vec3>> fixed;
    for (size_t i : kept) boxes.push_back({built[i].lo, built[i].hi}), fixed.push_back(parts[i].colour);
    const std::vector<Vec3> colours = assign_colours(boxes, fixed);
    std::vector<std::string> languages = {"en"};
    if (options.translations)
        for (const std::string& l : options.translations->languages)
            if (std::find(languages.begin(), languages.end(), l) == languages.end()) languages.push_back(l);

    const std::vector<std::string> stems = model_stems(parts);
    nlohmann::json models = nlohmann::json::array();
    std::vector<std::string> groups;
    for (size_t k = 0; k < kept.size(); ++k) {
        const Part& p = parts[kept[k]];
        const ReadableName rn = readable_name(p.name);
        nlohmann::json m;
        m["name"] = stems[kept[k]];
        m["file"] = files[kept[k]];
        std::string description = rn.side.empty() ? "" : rn.side + " side";
        if (options.groups) {
            const std::string g = options.groups->group_of(p.name, rn.side);
            m["group"] = g;
            if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
            description = readable_group(g);
        }
        const Vec3 c = colours[k];
        m["colour"] = {std::round(c.x * 1000) / 1000, std::round(c.y * 1000) / 1000, std::round(c.z * 1000) / 1000};
        const auto rot = kiosk_rotation_deg(proper_axes(p.ras_axes));
        if (rot != std::array<float, 3>{0, 0, 0}) m["transform"] = {{"rotate_deg", rot}};
        nlohmann::json label;
        label["en"] = {{"title", rn.with_side()}, {"description", description}};
        if (options.translations) {
            auto row = options.translations->rows.find(p.name);
            if (row == options.translations->rows.end()) row = options.translations->rows.find(stems[kept[k]]);
            if (row != options.translations->rows.end())
                for (const auto& [lang, t] : row->second)
                    label[lang] = {{"title", t.title}, {"description", t.description}};
        }
        m["label"] = std::move(label);
        models.push_back(std::move(m));
    }
    std::sort(groups.begin(), groups.end());
    nlohmann::json group_list = nlohmann::json::array();
    for (const std::string& g : groups) group_list.push_back({{"name", g}, {"visible", true}});
    nlohmann::json scene;
    scene["version"] = 1;
    scene["models"] = std::move(models);
    if (!group_list.empty()) scene["groups"] = std::move(group_list);
    scene["camera"] = {{"azimuth_deg", view_azimuth_deg(options.view)}, {"polar_deg", 90}};
    scene["kiosk"] = {{"languages", languages}};
    add_slices(parts, kept, scene);
    return scene;
}

}  // namespace body::exhibit
