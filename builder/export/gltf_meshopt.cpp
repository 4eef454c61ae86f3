// EXT_meshopt_compression for a GLB (contract in gltf_writer.h).
// Reference: Khronos glTF extension EXT_meshopt_compression (meshoptimizer
// vertex codec version 0, index codec version 1; a fallback buffer without data).
#include <meshoptimizer.h>

#include <cstring>
#include <nlohmann/json.hpp>

#include "builder/export/gltf_writer.h"

namespace body::exporter {
namespace {

uint32_t get_u32(std::span<const uint8_t> b, size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    out.insert(out.end(), p, p + 4);
}

// Encodes one view; `stride` 0 = an index view of `count` indices of `index_size` bytes.
std::vector<uint8_t> encode_view(const uint8_t* data, size_t length, size_t stride, size_t index_size) {
    std::vector<uint8_t> out;
    if (stride > 0) {
        const size_t count = length / stride;
        out.resize(meshopt_encodeVertexBufferBound(count, stride));
        out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride));
        return out;
    }
    const size_t count = length / index_size;
    std::vector<uint32_t> indices(count);
    for (size_t i = 0; i < count; ++i) {
        if (index_size == 2) {
            uint16_t v;
            std::memcpy(&v, data + i * 2, 2);
            indices[i] = v;
        } else {
            std::memcpy(&indices[i], data + i * 4, 4);
        }
    }
    size_t vertices = 0;
    for (uint32_t i : indices) vertices = std::max<size_t>(vertices, i + 1);
    out.resize(meshopt_encodeIndexBufferBound(count, vertices));
    out.resize(meshopt_encodeIndexBuffer(out.data(), out.size(), indices.data(), count));
    return out;
}

}  // namespace

Result<std::vector<uint8_t>> meshopt_compress_glb(std::span<const uint8_t> glb) {
    if (glb.size() < 28 || get_u32(glb, 0) != 0x46546C67u) return runtime_error("not a GLB");
    const uint32_t json_len = get_u32(glb, 12);
    if (20 + size_t(json_len) + 8 > glb.size()) return runtime_error("GLB without a binary chunk");
    nlohmann::json j = nlohmann::json::parse(glb.begin() + 20, glb.begin() + 20 + json_len, nullptr, false);
    if (j.is_discarded()) return runtime_error("GLB with unreadable JSON");
    const size_t bin_at = 20 + json_len + 8;
    const uint32_t bin_len = get_u32(glb, 20 + json_len);
    const uint8_t* bin = glb.data() + bin_at;

    meshopt_encodeVertexVersion(0);
    meshopt_encodeIndexVersion(1);
    // Index views: those an accessor of a primitive's `indices` reads.
    std::vector<size_t> index_size(j["bufferViews"].size(), 0);
    for (const auto& mesh : j["meshes"])
        for (const auto& prim : mesh["primitives"]) {
            const auto& acc = j["accessors"][prim["indices"].get<size_t>()];
            index_size[acc["bufferView"].get<size_t>()] = acc["componentType"] == 5123 ? 2 : 4;
        }
    std::vector<uint8_t> packed;
    for (size_t v = 0; v < j["bufferViews"].size(); ++v) {
        auto& view = j["bufferViews"][v];
        const size_t offset = view.value("byteOffset", size_t(0)), length = view["byteLength"];
        const size_t stride = index_size[v] ? 0 : view.value("byteStride", size_t(12));
        std::vector<uint8_t> enc = encode_view(bin + offset, length, stride, index_size[v]);
        while (packed.size() % 4) packed.push_back(0);
        nlohmann::json ext = {{"buffer", 0},
                              {"byteOffset", packed.size()},
                              {"byteLength", enc.size()},
                              {"byteStride", stride ? stride : index_size[v]},
                              {"count", stride ? length / stride : length / index_size[v]},
                              {"mode", stride ? "ATTRIBUTES" : "TRIANGLES"}};
        packed.insert(packed.end(), enc.begin(), enc.end());
        view["buffer"] = 1;
        view["extensions"]["EXT_meshopt_compression"] = ext;
    }
    while (packed.size() % 4) packed.push_back(0);
    j["buffers"] = nlohmann::json::array(
        {{{"byteLength", packed.size()}},
         {{"byteLength", bin_len}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
    for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
        if (!j.contains(key)) j[key] = nlohmann::json::array();
        j[key].push_back("EXT_meshopt_compression");
    }
    std::string text = j.dump();
    while (text.size() % 4) text.push_back(' ');
    std::vector<uint8_t> out;
    put_u32(out, 0x46546C67u);  // "glTF"
    put_u32(out, 2);
    put_u32(out, uint32_t(12 + 8 + text.size() + 8 + packed.size()));
    put_u32(out, uint32_t(text.size()));
    put_u32(out, 0x4E4F534Au);  // "JSON"
    out.insert(out.end(), text.begin(), text.end());
    put_u32(out, uint32_t(packed.size()));
    put_u32(out, 0x004E4942u);  // "BIN\0"
    out.insert(out.end(), packed.begin(), packed.end());
    return out;
}

}  // namespace body::exporter
