// glTF: The Khronos Group, "glTF 2.0 Specification", sections 3.6 (buffers,
// views, accessors) and 3.7.2 (meshes). Contract in gltf_check.h.
#include "builder/mesh_import/gltf_check.h"

#include <cctype>
#include <filesystem>

#include "shared/atomic_file.h"

#ifdef BODY_WITH_GLTF
#include <tiny_gltf.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "builder/export/gltf_writer.h"
#endif

namespace body {

#ifdef BODY_WITH_GLTF
namespace {

// Read external buffers through read_file (regular files only: no FIFO or
// device waits) and take URIs as written (tinygltf's default expands them
// with wordexp).
bool read_whole(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    auto bytes = read_file(path);
    if (!bytes) {
        *err += bytes.error().message;
        return false;
    }
    out->assign(bytes->begin(), bytes->end());
    return true;
}
bool exists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
}
std::string as_written(const std::string& path, void*) { return path; }
bool no_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    *err += "writing is not allowed";
    return false;
}

// tinygltf's error text as one line of at most 200 characters (it quotes whole data URIs).
std::string one_line(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
    if (s.size() > 200) s = s.substr(0, 200) + "...";
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ';';
    return s;
}

Status fault(const std::string& path, const std::string& place, const std::string& reason) {
    return input_error(path + ": glTF " + place + ": " + reason);
}

std::string n(size_t v) { return std::to_string(v); }

Status check_views(const tinygltf::Model& m, const std::string& path) {
    for (size_t v = 0; v < m.bufferViews.size(); ++v) {
        const tinygltf::BufferView& view = m.bufferViews[v];
        const std::string place = "bufferView " + n(v);
        if (view.buffer < 0 || size_t(view.buffer) >= m.buffers.size())
            return fault(path, place, "buffer " + std::to_string(view.buffer) + " does not exist");
        const size_t size = m.buffers[size_t(view.buffer)].data.size();
        if (view.byteOffset > size || view.byteLength > size - view.byteOffset)
            return fault(path, place,
                         "bytes " + n(view.byteOffset) + " + " + n(view.byteLength) + " run past buffer " +
                             std::to_string(view.buffer) + " (" + n(size) + " bytes)");
    }
    return ok_status();
}

// Byte stride of accessor `a` in its view (0 when it has no view).
size_t stride_of(const tinygltf::Model& m, const tinygltf::Accessor& a) {
    const size_t element = size_t(tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType))) *
                           size_t(tinygltf::GetNumComponentsInType(uint32_t(a.type)));
    if (a.bufferView < 0) return 0;
    const size_t given = m.bufferViews[size_t(a.bufferView)].byteStride;
    return given ? given : element;
}

Status check_accessor(const tinygltf::Model& m, size_t i, const std::string& path) {
    const tinygltf::Accessor& a = m.accessors[i];
    const std::string place = "accessor " + n(i);
    if (a.sparse.isSparse) return fault(path, place, "sparse accessors are not read");
    const int component = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
    const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
    if (component <= 0) return fault(path, place, "unknown component type " + std::to_string(a.componentType));
    if (components <= 0) return fault(path, place, "unknown type " + std::to_string(a.type));
    if (a.count == 0) return fault(path, place, "count 0 (at least 1 needed)");
    if (a.bufferView < 0) return ok_status();  // all zeros
    if (size_t(a.bufferView) >= m.bufferViews.size())
        return fault(path, place, "bufferView " + std::to_string(a.bufferView) + " does not exist");
    const size_t element = size_t(component) * size_t(components);
    const size_t stride = stride_of(m, a);
    if (stride < element || stride % size_t(component) != 0)
        return fault(path, place,
                     "byte stride " + n(stride) + " is below the element's " + n(element) +
                         " bytes or not a multiple of " + std::to_string(component));
    const size_t length = m.bufferViews[size_t(a.bufferView)].byteLength;
    const bool fits = a.byteOffset <= length && (a.count - 1) <= (length - a.byteOffset) / stride &&
                      element <= length - a.byteOffset - (a.count - 1) * stride;
    if (!fits)
        return fault(path, place,
                     "offset " + n(a.byteOffset) + " + (count " + n(a.count) + " - 1) x stride " + n(stride) +
                         " + element " + n(element) + " runs past bufferView " + std::to_string(a.bufferView) + " (" +
                         n(length) + " bytes)");
    return ok_status();
}

// Element `e`, component `k` of a checked accessor, as stored (zero without a view).
template <typename T>
T value_at(const tinygltf::Model& m, const tinygltf::Accessor& a, size_t e, size_t k) {
    T v{};
    if (a.bufferView < 0) return v;
    const tinygltf::BufferView& view = m.bufferViews[size_t(a.bufferView)];
    const size_t at = view.byteOffset + a.byteOffset + e * stride_of(m, a) + k * sizeof(T);
    std::memcpy(&v, m.buffers[size_t(view.buffer)].data.data() + at, sizeof(T));  // little-endian host
    return v;
}

uint64_t index_at(const tinygltf::Model& m, const tinygltf::Accessor& a, size_t e) {
    switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return value_at<uint8_t>(m, a, e, 0);
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return value_at<uint16_t>(m, a, e, 0);
        default: return value_at<uint32_t>(m, a, e, 0);
    }
}

Status check_primitive(const tinygltf::Model& m, size_t mi, size_t pi, const std::string& path) {
    const tinygltf::Primitive& p = m.meshes[mi].primitives[pi];
    const std::string place = "mesh " + n(mi) + " primitive " + n(pi);
    const bool list = p.mode == -1 || p.mode == TINYGLTF_MODE_TRIANGLES;
    if (!list && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP && p.mode != TINYGLTF_MODE_TRIANGLE_FAN)
        return fault(path, place,
                     "mode " + std::to_string(p.mode) + " is not a surface (triangles, strip or fan are read)");
    for (const auto& [semantic, index] : p.attributes)
        if (index < 0 || size_t(index) >= m.accessors.size())
            return fault(path, place, semantic + " accessor " + std::to_string(index) + " does not exist");
    const auto found = p.attributes.find("POSITION");
    if (found == p.attributes.end()) return fault(path, place, "no POSITION attribute");
    const size_t pos_index = size_t(found->second);
    const tinygltf::Accessor& pos = m.accessors[pos_index];
    const std::string pos_place = place + " accessor " + n(pos_index) + " (POSITION)";
    if (pos.type != TINYGLTF_TYPE_VEC3 || pos.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
        return fault(path, pos_place, "not VEC3 of float (component type " + std::to_string(pos.componentType) + ")");
    for (size_t e = 0; e < pos.count; ++e)
        for (size_t k = 0; k < 3; ++k)
            if (!std::isfinite(value_at<float>(m, pos, e, k)))
                return fault(path, pos_place + " element " + n(e), "coordinate " + n(k) + " is not finite");
    for (const auto& [semantic, index] : p.attributes)
        if (m.accessors[size_t(index)].count != pos.count)
            return fault(
                path, place + " accessor " + std::to_string(index) + " (" + semantic + ")",
                "count " + n(m.accessors[size_t(index)].count) + " differs from the POSITION count " + n(pos.count));
    if (p.indices < 0) {
        if (list && pos.count % 3 != 0)
            return fault(path, pos_place, "count " + n(pos.count) + " (no indices) is not a multiple of 3");
        return ok_status();
    }
    if (size_t(p.indices) >= m.accessors.size())
        return fault(path, place, "indices accessor " + std::to_string(p.indices) + " does not exist");
    const tinygltf::Accessor& ix = m.accessors[size_t(p.indices)];
    const std::string ix_place = place + " accessor " + std::to_string(p.indices) + " (indices)";
    const int c = ix.componentType;
    if (ix.type != TINYGLTF_TYPE_SCALAR ||
        (c != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && c != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
         c != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        return fault(path, ix_place,
                     "not SCALAR of unsigned byte, short or int (component type " + std::to_string(c) + ")");
    if (list && ix.count % 3 != 0) return fault(path, ix_place, "count " + n(ix.count) + " is not a multiple of 3");
    for (size_t e = 0; e < ix.count; ++e)
        if (const uint64_t v = index_at(m, ix, e); v >= pos.count)
            return fault(path, ix_place + " element " + n(e),
                         "index " + std::to_string(v) + " is not below the POSITION count " + n(pos.count));
    return ok_status();
}

}  // namespace

Status check_gltf_bytes(std::string_view bytes, bool binary, const std::string& path, const std::string& base_dir) {
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) return input_error(path + ": glTF: larger than 4 GiB");
    exporter::link_tinygltf();  // our tinygltf, not libdraco's (see gltf_writer.h)
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks(tinygltf::FsCallbacks{exists, as_written, read_whole, no_write, nullptr});
    tinygltf::Model model;
    std::string err, warn;
    const auto length = static_cast<unsigned int>(bytes.size());
    const bool parsed =
        binary ? loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                             length, base_dir)
               : loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), length, base_dir);
    if (!parsed) return input_error(path + ": glTF: " + (err.empty() ? "not readable" : one_line(err)));
    if (Status s = check_views(model, path); !s) return s;
    for (size_t i = 0; i < model.accessors.size(); ++i)
        if (Status s = check_accessor(model, i, path); !s) return s;
    for (size_t mi = 0; mi < model.meshes.size(); ++mi)
        for (size_t pi = 0; pi < model.meshes[mi].primitives.size(); ++pi)
            if (Status s = check_primitive(model, mi, pi, path); !s) return s;
    return ok_status();
}

#else

Status check_gltf_bytes(std::string_view, bool, const std::string&, const std::string&) { return ok_status(); }

#endif

Status check_gltf_file(const std::string& path) {
    auto bytes = read_file(path);  // checks for a regular file first
    if (!bytes) return bytes.error();
    const std::filesystem::path p(path);
    std::string ext = p.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    const std::string base = p.has_parent_path() ? p.parent_path().string() : ".";
    return check_gltf_bytes(*bytes, ext == ".glb", path, base);
}

}  // namespace body
