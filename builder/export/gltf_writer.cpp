// ExportScene -> glTF 2.0 with tinygltf (layout in gltf_writer.h).
// Reference: The Khronos Group, "glTF 2.0 Specification", 2021.
#define TINYGLTF_IMPLEMENTATION
#include "builder/export/gltf_writer.h"

#include <meshoptimizer.h>
#include <tiny_gltf.h>

#include <cstring>
#include <filesystem>
#include <map>
#include <sstream>

#include "shared/atomic_file.h"

namespace body::exporter {

void link_tinygltf() {}
namespace {

// Appends `bytes` to the one buffer, 4-byte aligned; returns its buffer view.
int add_view(tinygltf::Model& g, const void* bytes, size_t size, int target) {
    auto& data = g.buffers[0].data;
    while (data.size() % 4) data.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = size;
    view.target = target;
    data.insert(data.end(), static_cast<const unsigned char*>(bytes), static_cast<const unsigned char*>(bytes) + size);
    g.bufferViews.push_back(view);
    return int(g.bufferViews.size() - 1);
}

int add_vec3_accessor(tinygltf::Model& g, const std::vector<float>& xyz, bool bounds) {
    tinygltf::Accessor a;
    a.bufferView = add_view(g, xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = xyz.size() / 3;
    if (bounds) {
        a.minValues = {1e300, 1e300, 1e300};
        a.maxValues = {-1e300, -1e300, -1e300};
        for (size_t i = 0; i < xyz.size(); ++i) {
            a.minValues[i % 3] = std::min(a.minValues[i % 3], double(xyz[i]));
            a.maxValues[i % 3] = std::max(a.maxValues[i % 3], double(xyz[i]));
        }
    }
    g.accessors.push_back(a);
    return int(g.accessors.size() - 1);
}

int add_indices(tinygltf::Model& g, const std::vector<uint32_t>& indices, size_t vertices) {
    tinygltf::Accessor a;
    a.count = indices.size();
    a.type = TINYGLTF_TYPE_SCALAR;
    if (vertices <= 65535) {  // 65535 is the primitive-restart value, never an index
        std::vector<uint16_t> shorts(indices.begin(), indices.end());
        a.bufferView =
            add_view(g, shorts.data(), shorts.size() * sizeof(uint16_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    } else {
        a.bufferView =
            add_view(g, indices.data(), indices.size() * sizeof(uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    }
    g.accessors.push_back(a);
    return int(g.accessors.size() - 1);
}

// KHR_mesh_quantization: positions as uint16 codes over the bounds (stride 8);
// returns the code -> model matrix (column-major) and fills the accessor.
std::vector<double> add_quantized_positions(tinygltf::Model& g, const Mesh& mesh, int& accessor) {
    Vec3 lo(1e300), hi(-1e300);
    for (const Vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    Vec3 step = (hi - lo) / 65535.0;
    for (int k = 0; k < 3; ++k)
        if (!(step[k] > 0.0)) step[k] = 1.0;
    std::vector<uint16_t> codes;
    uint16_t cmin[3] = {65535, 65535, 65535}, cmax[3] = {0, 0, 0};
    for (const Vec3& p : mesh.positions) {
        for (int k = 0; k < 3; ++k) {
            const auto c = uint16_t(std::clamp(std::lround((p[k] - lo[k]) / step[k]), 0L, 65535L));
            codes.push_back(c);
            cmin[k] = std::min(cmin[k], c), cmax[k] = std::max(cmax[k], c);
        }
        codes.push_back(0);
    }
    tinygltf::Accessor a;
    a.bufferView = add_view(g, codes.data(), codes.size() * 2, TINYGLTF_TARGET_ARRAY_BUFFER);
    g.bufferViews.back().byteStride = 8;
    a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = mesh.positions.size();
    a.minValues = {double(cmin[0]), double(cmin[1]), double(cmin[2])};
    a.maxValues = {double(cmax[0]), double(cmax[1]), double(cmax[2])};
    g.accessors.push_back(a);
    accessor = int(g.accessors.size() - 1);
    return {step.x, 0, 0, 0, 0, step.y, 0, 0, 0, 0, step.z, 0, lo.x, lo.y, lo.z, 1};
}

int add_quantized_normals(tinygltf::Model& g, const Mesh& mesh) {
    std::vector<int16_t> codes;
    for (const Vec3& n : mesh.normals) {
        const Vec3 u = glm::normalize(n);
        for (int k = 0; k < 3; ++k) codes.push_back(int16_t(std::lround(u[k] * 32767.0)));
        codes.push_back(0);
    }
    tinygltf::Accessor a;
    a.bufferView = add_view(g, codes.data(), codes.size() * 2, TINYGLTF_TARGET_ARRAY_BUFFER);
    g.bufferViews.back().byteStride = 8;
    a.componentType = TINYGLTF_COMPONENT_TYPE_SHORT;
    a.normalized = true;
    a.type = TINYGLTF_TYPE_VEC3;
    a.count = mesh.normals.size();
    g.accessors.push_back(a);
    return int(g.accessors.size() - 1);
}

std::vector<double> multiply_column_major(const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> r(16, 0.0);
    for (int c = 0; c < 4; ++c)
        for (int rr = 0; rr < 4; ++rr)
            for (int k = 0; k < 4; ++k) r[size_t(c * 4 + rr)] += a[size_t(k * 4 + rr)] * b[size_t(c * 4 + k)];
    return r;
}

// Vertex cache then fetch order (as gltfpack does before compressing): the
// meshopt codecs need it to compress well; the geometry is unchanged.
Mesh cache_ordered(const Mesh& in) {
    Mesh m = in;
    meshopt_optimizeVertexCache(m.indices.data(), in.indices.data(), in.indices.size(), in.positions.size());
    std::vector<uint32_t> remap(in.positions.size());
    const size_t n = meshopt_optimizeVertexFetchRemap(remap.data(), m.indices.data(), m.indices.size(), remap.size());
    meshopt_remapIndexBuffer(m.indices.data(), m.indices.data(), m.indices.size(), remap.data());
    m.positions.assign(n, Vec3(0.0));
    for (size_t v = 0; v < remap.size(); ++v)
        if (remap[v] != ~0u) m.positions[remap[v]] = in.positions[v];
    if (in.normals.size() == in.positions.size()) {
        m.normals.assign(n, Vec3(0, 0, 1));
        for (size_t v = 0; v < remap.size(); ++v)
            if (remap[v] != ~0u) m.normals[remap[v]] = in.normals[v];
    }
    return m;
}

int add_model(tinygltf::Model& g, const ExportModel& source, bool quantize) {
    ExportModel reordered;
    if (quantize) {
        reordered.name = source.name;
        reordered.matrix = source.matrix;
        reordered.mesh = cache_ordered(source.mesh);
    }
    const ExportModel& m = quantize ? reordered : source;
    std::vector<float> positions, normals;
    for (const Vec3& p : m.mesh.positions) positions.insert(positions.end(), {float(p.x), float(p.y), float(p.z)});
    if (m.mesh.normals.size() == m.mesh.positions.size()) {
        for (const Vec3& n : m.mesh.normals) {
            const glm::vec3 u = glm::normalize(glm::vec3(n));  // unit in float, as the validator checks
            normals.insert(normals.end(), {u.x, u.y, u.z});
        }
    }
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    std::vector<double> dequantize;
    if (quantize) {
        int accessor = -1;
        dequantize = add_quantized_positions(g, m.mesh, accessor);
        prim.attributes["POSITION"] = accessor;
        if (!normals.empty()) prim.attributes["NORMAL"] = add_quantized_normals(g, m.mesh);
    } else {
        prim.attributes["POSITION"] = add_vec3_accessor(g, positions, true);
        if (!normals.empty()) prim.attributes["NORMAL"] = add_vec3_accessor(g, normals, false);
    }
    prim.indices = add_indices(g, m.mesh.indices, m.mesh.positions.size());

    tinygltf::Material mat;
    mat.name = m.name;
    mat.pbrMetallicRoughness.baseColorFactor = {m.mesh.color.x, m.mesh.color.y, m.mesh.color.z, 1.0};
    mat.pbrMetallicRoughness.metallicFactor = 0.0;
    mat.pbrMetallicRoughness.roughnessFactor = 0.7;
    g.materials.push_back(mat);
    prim.material = int(g.materials.size() - 1);

    tinygltf::Mesh mesh;
    mesh.name = m.name;
    mesh.primitives.push_back(prim);
    g.meshes.push_back(mesh);

    tinygltf::Node node;
    node.name = m.name;
    node.mesh = int(g.meshes.size() - 1);
    bool identity = true;
    std::vector<double> column_major(16);
    for (size_t c = 0; c < 4; ++c)
        for (size_t r = 0; r < 4; ++r) {
            column_major[c * 4 + r] = m.matrix[r][c];
            identity = identity && m.matrix[r][c] == (r == c ? 1.0 : 0.0);
        }
    if (!dequantize.empty()) {
        node.matrix = multiply_column_major(column_major, dequantize);
    } else if (!identity) {
        node.matrix = column_major;
    }
    g.nodes.push_back(node);
    return int(g.nodes.size() - 1);
}

}  // namespace

Status write_gltf(const std::string& path, const ExportScene& scene, const GltfOptions& options) {
    tinygltf::Model g;
    g.asset.version = "2.0";
    g.asset.generator = "bodygen export";
    g.buffers.emplace_back();
    tinygltf::Node root;
    root.name = std::filesystem::path(path).stem().string();
    root.scale = {0.001, 0.001, 0.001};  // scene millimetres -> glTF metres
    std::map<std::string, int> group_node;
    std::vector<int> top;
    for (const std::string& name : scene.groups) {
        tinygltf::Node n;
        n.name = name;
        g.nodes.push_back(n);
        group_node[name] = int(g.nodes.size() - 1);
    }
    for (const ExportModel& m : scene.models) {
        if (m.mesh.triangle_count() == 0) continue;  // glTF accessors must not be empty
        const int node = add_model(g, m, options.meshopt);
        auto it = m.group.empty() ? group_node.end() : group_node.find(m.group);
        if (it == group_node.end())
            top.push_back(node);
        else
            g.nodes[size_t(it->second)].children.push_back(node);
    }
    for (const auto& [name, node] : group_node)
        if (!g.nodes[size_t(node)].children.empty()) root.children.push_back(node);
    root.children.insert(root.children.end(), top.begin(), top.end());
    // Empty groups stay out of the tree; the validator flags unused nodes.
    std::vector<tinygltf::Node> kept;
    std::vector<int> remap(g.nodes.size(), -1);
    for (size_t i = 0; i < g.nodes.size(); ++i) {
        const bool empty_group = g.nodes[i].mesh < 0 && g.nodes[i].children.empty();
        if (!empty_group) remap[i] = int(kept.size()), kept.push_back(g.nodes[i]);
    }
    for (auto& n : kept)
        for (int& c : n.children) c = remap[size_t(c)];
    for (int& c : root.children) c = remap[size_t(c)];
    g.nodes = std::move(kept);
    g.nodes.push_back(root);
    tinygltf::Scene s;
    s.name = root.name;
    s.nodes = {int(g.nodes.size() - 1)};
    g.scenes.push_back(s);
    g.defaultScene = 0;

    if (options.meshopt) {
        if (!options.binary) return input_error(path + ": meshopt compression is for .glb files only");
        g.extensionsUsed = {"KHR_mesh_quantization"};
        g.extensionsRequired = {"KHR_mesh_quantization"};
    }
    tinygltf::TinyGLTF writer;
    std::ostringstream out;
    if (!writer.WriteGltfSceneToStream(&g, out, !options.binary, options.binary))
        return runtime_error(path + ": the glTF writer failed");
    const std::string text = out.str();
    std::vector<uint8_t> bytes(text.begin(), text.end());
    if (options.meshopt) {
        auto packed = meshopt_compress_glb(bytes);
        if (!packed) return runtime_error(path + ": " + packed.error().message);
        bytes = std::move(*packed);
    }
    return write_file_atomically(path, bytes);
}

}  // namespace body::exporter
