// The PLY, STL, GLB and glTF checks that run before assimp (builder/mesh_import/
// ply_check.h, stl_check.h, glb_check.h, gltf_check.h) and the OBJ line checks (shared/obj_io.cpp):
// every count that disagrees with the data is refused with its place, and
// well-formed files pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include "builder/mesh_import/glb_check.h"
#include "builder/mesh_import/gltf_check.h"
#include "builder/mesh_import/ply_check.h"
#include "builder/mesh_import/stl_check.h"
#include "shared/obj_io.h"

namespace body {
namespace {

const float kTetra[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};

std::string ply_head(const std::string& format, int vertices = 4, int faces = 4) {
    return "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(vertices) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
           "\nproperty list uchar int vertex_indices\nend_header\n";
}

std::string ascii_vertices() {
    std::string s;
    for (const auto& v : kTetra)
        s += std::to_string(int(v[0])) + " " + std::to_string(int(v[1])) + " " + std::to_string(int(v[2])) + "\n";
    return s;
}

std::string ascii_ply(const std::string& faces, int face_count = 4) {
    return ply_head("ascii", 4, face_count) + ascii_vertices() + faces;
}

const char* kFaceRows = "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n";

template <typename T>
void put(std::string& s, T v) {
    s.append(reinterpret_cast<const char*>(&v), sizeof v);  // little-endian host (x86-64, aarch64)
}

std::string binary_ply(unsigned char list_count = 3, int face_count = 4) {
    std::string s = ply_head("binary_little_endian", 4, face_count);
    for (const auto& v : kTetra)
        for (float c : v) put(s, c);
    for (const auto& f : kFaces) {
        put(s, list_count);
        for (int i : f) put(s, int32_t(i));
    }
    return s;
}

std::string binary_stl(uint32_t count = 4, float poison = 0) {
    std::string s(80, '\0');
    put(s, count);
    for (const auto& f : kFaces) {
        for (int k = 0; k < 3; ++k) put(s, 0.0f);
        for (int i : f)
            for (float c : kTetra[i]) put(s, c + poison);
        put(s, uint16_t(0));
    }
    return s;
}

std::string ascii_stl(const std::string& vertices, const std::string& tail = "endsolid x\n") {
    return "solid x\nfacet normal 0 0 1\nouter loop\n" + vertices + "endloop\nendfacet\n" + tail;
}
const char* kThree = "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n";

void expect_refused(const Status& s, const std::string& shape) {
    ASSERT_FALSE(s.ok()) << "accepted; expected /" << shape << "/";
    EXPECT_TRUE(std::regex_search(s.error().message, std::regex(shape)))
        << "expected /" << shape << "/ in: " << s.error().message;
    EXPECT_EQ(s.error().message.find('\n'), std::string::npos);
}

TEST(PlyCheck, WellFormedAsciiAndBinaryPass) {
    EXPECT_TRUE(check_ply_bytes(ascii_ply(kFaceRows), "m.ply").ok());
    EXPECT_TRUE(check_ply_bytes(ascii_ply(std::string(kFaceRows) + "\n\n"), "m.ply").ok());  // trailing blank lines
    EXPECT_TRUE(check_ply_bytes(binary_ply(), "m.ply").ok());
}

TEST(PlyCheck, AsciiListCountThatDisagreesWithItsValuesIsRefusedAtItsLine) {
    // 9 header lines: vertex rows on lines 10-13, face rows from line 14.
    expect_refused(check_ply_bytes(ascii_ply("255 0 1 2\n3 0 1 3\n3 1 2 3\n3 2 0 3\n"), "m.ply"),
                   "^m\\.ply: PLY line 14 \\(element 'face' row 1\\): list 'vertex_indices' declares 255 values, "
                   "the row holds 3$");
    expect_refused(check_ply_bytes(ascii_ply("3 0 2 1\n3 0 1 3 2\n3 1 2 3\n3 2 0 3\n"), "m.ply"),
                   "^m\\.ply: PLY line 15 \\(element 'face' row 2\\): the row has 5 values, its properties take 4$");
}

TEST(PlyCheck, AsciiRowsMissingOrLeftOverAreRefused) {
    expect_refused(check_ply_bytes(ascii_ply("3 0 2 1\n3 0 1 3\n"), "m.ply"),
                   "PLY line .* \\(element 'face' row 3\\): missing: the file ends after 2 of 4 rows");
    expect_refused(check_ply_bytes(ascii_ply(kFaceRows, 3), "m.ply"),
                   "^m\\.ply: PLY line 17: data after the last element's rows$");
    const std::string short_vertex = ply_head("ascii") + "0 0\n1 0 0\n0 1 0\n0 0 1\n" + kFaceRows;
    expect_refused(check_ply_bytes(short_vertex, "m.ply"),
                   "PLY line 10 \\(element 'vertex' row 1\\): the row has 2 values; property 'z' has none");
}

TEST(PlyCheck, AsciiValuesOutsideTheirTypeAreRefused) {
    const std::string nan_vertex = ply_head("ascii") + "nan 0 0\n1 0 0\n0 1 0\n0 0 1\n" + kFaceRows;
    expect_refused(check_ply_bytes(nan_vertex, "m.ply"), "row 1\\): 'x' nan is not a finite float");
    expect_refused(check_ply_bytes(ascii_ply("300 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n"), "m.ply"),
                   "list count 'vertex_indices' 300 is outside its type's range");
    expect_refused(check_ply_bytes(ascii_ply("3 0 2 9\n3 0 1 3\n3 1 2 3\n3 2 0 3\n"), "m.ply"),
                   "'vertex_indices' value 9 is not a vertex index \\(0\\.\\.3\\)");
    expect_refused(check_ply_bytes(ascii_ply("3 0 2 one\n3 0 1 3\n3 1 2 3\n3 2 0 3\n"), "m.ply"),
                   "'vertex_indices' value 'one' is not a number of its type");
}

TEST(PlyCheck, BinaryRowsMustFillTheFileExactly) {
    std::string trailing = binary_ply() + std::string(9, '\0');
    expect_refused(check_ply_bytes(trailing, "m.ply"),
                   "^m\\.ply: PLY byte [0-9]+: 9 bytes after the last element's rows$");
    expect_refused(check_ply_bytes(binary_ply(3, 3), "m.ply"), "13 bytes after the last element's rows");
    std::string cut = binary_ply();
    cut.resize(cut.size() - 20);
    expect_refused(check_ply_bytes(cut, "m.ply"), "the file ends inside the row");
    // A list count longer than its values reads the next row's bytes as indices.
    expect_refused(check_ply_bytes(binary_ply(9), "m.ply"), "PLY byte [0-9]+ \\(element 'face' row 1\\): .*");
}

TEST(PlyCheck, BinaryElementWithoutPropertiesIsNotWalkedRowByRow) {
    // Rows of no bytes: a count of 10^11 must not mean 10^11 loop turns (found by
    // fuzz_mesh_checks; walked row by row, this test would not end).
    std::string s = binary_ply();
    s.insert(s.find("element face"), "element nothing 100000000000\n");
    EXPECT_TRUE(check_ply_bytes(s, "m.ply").ok());
    s += "x";
    expect_refused(check_ply_bytes(s, "m.ply"), "1 bytes after the last element's rows");
}

TEST(PlyCheck, HeaderFaultsKeepTheirLine) {
    expect_refused(check_ply_bytes("ply\nformat ascii 1.0\nelement vertex 3\n", "m.ply"),
                   "PLY header line 3: no end_header");
    expect_refused(check_ply_bytes(ply_head("ascii", 1000000) + ascii_vertices(), "m.ply"),
                   "PLY header line 3: declares 1000000 rows");
}

TEST(StlCheck, WellFormedBinaryAndAsciiPass) {
    EXPECT_TRUE(check_stl_bytes(binary_stl(), "m.stl").ok());
    EXPECT_TRUE(check_stl_bytes(ascii_stl(kThree), "m.stl").ok());
    EXPECT_TRUE(check_stl_bytes(ascii_stl(kThree, "endsolid x\n") + ascii_stl(kThree, "endsolid\n"), "m.stl").ok());
}

TEST(StlCheck, BinaryCountMustMatchTheFileSize) {
    expect_refused(check_stl_bytes(binary_stl(5), "m.stl"),
                   "^m\\.stl: STL byte 80: binary STL declares 5 triangles \\(334 bytes\\), the file has 284 bytes$");
    expect_refused(check_stl_bytes(binary_stl(4) + "xyz", "m.stl"),
                   "declares 4 triangles \\(284 bytes\\), the file has 287");
    // 2^31 + 4 triangles: 50 * count + 84 wraps to the real size in 32 bits.
    expect_refused(check_stl_bytes(binary_stl(0x80000004u), "m.stl"), "declares 2147483652 triangles");
    expect_refused(check_stl_bytes(binary_stl(0).substr(0, 84), "m.stl"), "declares no triangles");
    expect_refused(check_stl_bytes(std::string(80, '\0'), "m.stl"), "80 bytes, less than its 84-byte header");
}

TEST(StlCheck, BinaryNonFiniteVertexIsRefusedAtItsByte) {
    expect_refused(check_stl_bytes(binary_stl(4, std::nanf("")), "m.stl"),
                   "^m\\.stl: STL byte 96 \\(triangle 1\\): vertex coordinate [-]?nan is not finite$");
}

TEST(StlCheck, AsciiGrammarFaultsAreRefusedAtTheirLine) {
    expect_refused(check_stl_bytes(ascii_stl(std::string(kThree) + "vertex 1 1 0\n"), "m.stl"),
                   "^m\\.stl: STL line 7: facet has more than 3 vertices, an STL facet has 3$");
    expect_refused(check_stl_bytes(ascii_stl("vertex 0 0 0\nvertex 1 0 0\n"), "m.stl"), "facet has 2 vertices");
    expect_refused(check_stl_bytes(ascii_stl("vertex 0 0 0\nvertex 1 0 0\nvertex 0 1\n"), "m.stl"),
                   "STL line 7: vertex needs 3 numbers, found 'endloop'");
    expect_refused(check_stl_bytes(ascii_stl("vertex 0 0 0\nvertex 1 0 0\nvertex 0 nan 0\n"), "m.stl"),
                   "STL line 6: vertex value 'nan' is not a finite float");
    expect_refused(check_stl_bytes(ascii_stl(kThree, ""), "m.stl"),
                   "expected 'facet' or 'endsolid', found the end of the file");
    expect_refused(check_stl_bytes(ascii_stl(kThree, "endsolid x\ngarbage\n"), "m.stl"),
                   "STL line 10: expected 'solid' or the end of the file, found 'garbage'");
    expect_refused(check_stl_bytes("solid x\nendsolid x\n", "m.stl"), "no facets");
}

TEST(ObjCheck, TextureAndNormalReferencesMustBeDefined) {
    const std::string tetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
    auto status = [](const std::string& text) -> Status {
        auto meshes = parse_obj(text, "m.obj");
        if (!meshes) return meshes.error();
        return ok_status();
    };
    EXPECT_TRUE(status(tetra + "vt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf 1//1 2//1 4//1\n").ok());
    EXPECT_TRUE(status("v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n").ok());  // vertex colours
    expect_refused(status(tetra + "f 1/9 2/9 3/9\n"),
                   "^m\\.obj: line 5: face texture coordinate index 9 is outside 1\\.\\.0 \\(the texture coordinates "
                   "defined so far\\)$");
    expect_refused(status(tetra + "vn 0 0 1\nf 1//2 2//1 3//1\n"), "line 6: face normal index 2 is outside 1\\.\\.1");
    expect_refused(status(tetra + "f 1//x 2 3\n"), "line 5: face vertex '1//x' is not an index");
    expect_refused(status(tetra + "f 1/1/1/1 2 3\n"), "line 5: face vertex '1/1/1/1' has more than 3 parts");
    expect_refused(status("v 0 0 0 1 1\n"), "line 1: vertex has 5 values");
    expect_refused(status("vt nan 0\n"), "line 1: texture coordinate 'nan' is not a finite float");
    expect_refused(status("vn 0 1\n"), "line 1: normal has 2 values");
}

// A .glb container: header length = file size, the first chunk JSON, every chunk inside the file.
std::string glb(std::string json, std::string bin, uint32_t length_delta = 0) {
    auto u32 = [](uint32_t v) { return std::string{char(v), char(v >> 8), char(v >> 16), char(v >> 24)}; };
    json.append((4 - json.size() % 4) % 4, ' ');
    std::string body = u32(uint32_t(json.size())) + "JSON" + json;
    if (!bin.empty()) body += u32(uint32_t(bin.size())) + std::string("BIN\0", 4) + bin;
    return "glTF" + u32(2) + u32(uint32_t(12 + body.size()) + length_delta) + body;
}

TEST(GlbCheck, ContainerFaultsAreRefusedAtTheirByte) {
    const std::string good = glb("{\"asset\":{\"version\":\"2.0\"}}", std::string(48, '\0'));
    EXPECT_TRUE(check_glb_bytes(good, "m.glb").ok());
    auto message = [](const std::string& bytes) {
        const Status s = check_glb_bytes(bytes, "m.glb");
        return s.ok() ? std::string("accepted") : s.error().message;
    };
    EXPECT_EQ(message(glb("{}", "", 1u << 30)),
              "m.glb: GLB byte 8: header length 1073741848 but the file has 24 bytes");
    EXPECT_EQ(message("glTX" + good.substr(4)), "m.glb: GLB byte 0: magic is not \"glTF\"");
    std::string v1 = good;
    v1[4] = 1;
    EXPECT_EQ(message(v1), "m.glb: GLB byte 4: version 1, only 2 is read");
    std::string long_chunk = good;
    long_chunk[12] = char(200);  // the JSON chunk's length past the end
    EXPECT_EQ(message(long_chunk).rfind("m.glb: GLB byte 12: chunk length 200 runs past the end", 0), 0u);
    std::string bin_first = glb("{}", "");
    bin_first.replace(16, 4, std::string("BIN\0", 4));
    EXPECT_EQ(message(bin_first), "m.glb: GLB byte 16: the first chunk is not JSON");
    EXPECT_EQ(message(good.substr(0, 11)), "m.glb: GLB byte 0: a 12-byte header needed, the file has 11");
}

// The tetrahedron as glTF: positions (48 bytes) then 12 unsigned short indices
// (24 bytes) in one buffer, a data URI (.gltf) or the BIN chunk (.glb).
std::string tetra_buffer(const std::vector<int>& indices, float poison = 0) {
    std::string data;
    for (int v = 0; v < 4; ++v)
        for (int k = 0; k < 3; ++k) put(data, kTetra[v][k] + (v == 2 && k == 1 ? poison : 0.0f));  // element 2, y
    for (int i : indices) put(data, uint16_t(i));
    return data;
}

std::string base64(const std::string& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const size_t have = std::min<size_t>(3, bytes.size() - i);  // bytes in this group
        uint32_t v = 0;
        for (size_t k = 0; k < 3; ++k) v = v << 8 | (k < have ? uint8_t(bytes[i + k]) : 0u);
        for (size_t k = 0; k < 4; ++k) out += k <= have ? digits[(v >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

// `uri` empty: the buffer lives in a .glb's BIN chunk.
std::string tetra_json(const std::string& uri, size_t data_size) {
    return "{\"asset\":{\"version\":\"2.0\"},\"scenes\":[{\"nodes\":[0]}],\"scene\":0,\"nodes\":[{\"mesh\":0}],"
           "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],"
           "\"buffers\":[{\"byteLength\":" +
           std::to_string(data_size) + (uri.empty() ? "" : ",\"uri\":\"" + uri + "\"") +
           "}],"
           "\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":48},"
           "{\"buffer\":0,\"byteOffset\":48,\"byteLength\":24}],"
           "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"type\":\"VEC3\",\"count\":4},"
           "{\"bufferView\":1,\"componentType\":5123,\"type\":\"SCALAR\",\"count\":12}]}";
}

std::vector<int> tetra_indices() {
    std::vector<int> out;
    for (const auto& f : kFaces) out.insert(out.end(), f, f + 3);
    return out;
}

// The check's message for the .gltf whose JSON has `from` replaced by `to` (the first).
std::string gltf_message(const std::string& from = "", const std::string& to = "",
                         const std::vector<int>& indices = tetra_indices(), float poison = 0) {
    const std::string data = tetra_buffer(indices, poison);
    std::string json = tetra_json("data:application/octet-stream;base64," + base64(data), data.size());
    if (!from.empty()) {
        const size_t at = json.find(from);
        if (at == std::string::npos) return "test fault: '" + from + "' not in the JSON";
        json.replace(at, from.size(), to);
    }
    const Status s = check_gltf_bytes(json, false, "m.gltf", ".");
    EXPECT_TRUE(s.ok() || s.error().message.find('\n') == std::string::npos);
    return s.ok() ? std::string("accepted") : s.error().message;
}

TEST(GltfCheck, WellFormedGltfAndGlbPass) {
#ifndef BODY_WITH_GLTF
    GTEST_SKIP() << "built without tinygltf: glTF is checked by assimp alone";
#endif
    EXPECT_EQ(gltf_message(), "accepted");
    EXPECT_EQ(gltf_message("\"indices\":1}", "\"indices\":1,\"mode\":5}"), "accepted");  // a strip
    const std::string data = tetra_buffer(tetra_indices());
    const std::string bytes = glb(tetra_json("", data.size()), data);
    ASSERT_TRUE(check_glb_bytes(bytes, "m.glb").ok());
    EXPECT_TRUE(check_gltf_bytes(bytes, true, "m.glb", ".").ok());
}

TEST(GltfCheck, IndexPastThePositionsIsRefusedAtItsElement) {
#ifndef BODY_WITH_GLTF
    GTEST_SKIP() << "built without tinygltf";
#endif
    std::vector<int> one_beyond = tetra_indices();
    one_beyond[11] = 99;  // three faces good, the fourth's last index past the 4 positions
    EXPECT_EQ(gltf_message("", "", one_beyond),
              "m.gltf: glTF mesh 0 primitive 0 accessor 1 (indices) element 11: index 99 is not below the POSITION "
              "count 4");
    const std::string data = tetra_buffer(one_beyond);
    const Status s = check_gltf_bytes(glb(tetra_json("", data.size()), data), true, "m.glb", ".");
    ASSERT_FALSE(s.ok());
    EXPECT_EQ(s.error().message.rfind("m.glb: glTF mesh 0 primitive 0 accessor 1 (indices) element 11: index 99", 0),
              0u);
}

TEST(GltfCheck, RangesOutsideTheirDataAreRefusedWithThePlace) {
#ifndef BODY_WITH_GLTF
    GTEST_SKIP() << "built without tinygltf";
#endif
    EXPECT_EQ(gltf_message("\"byteOffset\":48,\"byteLength\":24", "\"byteOffset\":48,\"byteLength\":4000"),
              "m.gltf: glTF bufferView 1: bytes 48 + 4000 run past buffer 0 (72 bytes)");
    EXPECT_EQ(gltf_message("\"count\":4", "\"count\":1000"),
              "m.gltf: glTF accessor 0: offset 0 + (count 1000 - 1) x stride 12 + element 12 runs past bufferView 0 "
              "(48 bytes)");
    EXPECT_EQ(gltf_message("\"bufferView\":1,", "\"bufferView\":1,\"byteOffset\":22,"),
              "m.gltf: glTF accessor 1: offset 22 + (count 12 - 1) x stride 2 + element 2 runs past bufferView 1 "
              "(24 bytes)");
    EXPECT_EQ(gltf_message("\"byteLength\":48}", "\"byteLength\":48,\"byteStride\":4}"),
              "m.gltf: glTF accessor 0: byte stride 4 is below the element's 12 bytes or not a multiple of 4");
    EXPECT_EQ(gltf_message("\"count\":12}",
                           "\"count\":1,\"sparse\":{\"count\":1,\"indices\":{\"bufferView\":1,"
                           "\"componentType\":5123},\"values\":{\"bufferView\":1}}}"),
              "m.gltf: glTF accessor 1: sparse accessors are not read");
}

TEST(GltfCheck, TypesModesAndValuesAreRefusedWithThePlace) {
#ifndef BODY_WITH_GLTF
    GTEST_SKIP() << "built without tinygltf";
#endif
    EXPECT_EQ(gltf_message("\"indices\":1}", "\"indices\":1,\"mode\":1}"),
              "m.gltf: glTF mesh 0 primitive 0: mode 1 is not a surface (triangles, strip or fan are read)");
    EXPECT_EQ(gltf_message("5123,\"type\":\"SCALAR\",\"count\":12", "5126,\"type\":\"SCALAR\",\"count\":6"),
              "m.gltf: glTF mesh 0 primitive 0 accessor 1 (indices): not SCALAR of unsigned byte, short or int "
              "(component type 5126)");
    EXPECT_EQ(gltf_message("5126", "5122"),
              "m.gltf: glTF mesh 0 primitive 0 accessor 0 (POSITION): not VEC3 of float (component type 5122)");
    EXPECT_EQ(gltf_message("\"count\":12", "\"count\":11"),
              "m.gltf: glTF mesh 0 primitive 0 accessor 1 (indices): count 11 is not a multiple of 3");
    EXPECT_EQ(gltf_message("", "", tetra_indices(), std::numeric_limits<float>::infinity()),
              "m.gltf: glTF mesh 0 primitive 0 accessor 0 (POSITION) element 2: coordinate 1 is not finite");
    EXPECT_EQ(gltf_message("\"POSITION\":0", "\"NORMAL\":0"), "m.gltf: glTF mesh 0 primitive 0: no POSITION attribute");
    const std::string broken = gltf_message("{\"asset\"", "{ not json \"asset\"");
    EXPECT_EQ(broken.rfind("m.gltf: glTF: ", 0), 0u) << broken;
    const std::string truncated = gltf_message(";base64,AAAA", ";base64,AAA");  // quoted by tinygltf, cut short
    EXPECT_EQ(truncated.rfind("m.gltf: glTF: ", 0), 0u) << truncated;
    EXPECT_LE(truncated.size(), 230u) << truncated;
}

}  // namespace
}  // namespace body
