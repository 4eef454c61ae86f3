// The benchmark's stand-in model (contract in benchmark.h): the bunny, or a
// bumpy icosphere where it is not installed, subdivided toward the asked-for size;
// and the frame timer and median every table uses.
#include <GLES3/gl3.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_map>

#include "kiosk/modes/benchmark.h"
#include "shared/edge_key.h"
#include "shared/obj_io.h"

namespace body::kiosk {
namespace {

// Midpoint subdivision (each triangle -> 4) with shared edge midpoints.
void subdivide(std::vector<Vec3f>& p, std::vector<uint32_t>& idx) {
    std::unordered_map<uint64_t, uint32_t> mid;
    mid.reserve(idx.size());
    auto midpoint = [&](uint32_t a, uint32_t b) {
        auto [it, inserted] = mid.emplace(edge_key(a, b), static_cast<uint32_t>(p.size()));
        if (inserted) p.push_back((p[a] + p[b]) * 0.5f);
        return it->second;
    };
    std::vector<uint32_t> out;
    out.reserve(idx.size() * 4);
    for (size_t f = 0; f + 2 < idx.size(); f += 3) {
        uint32_t a = idx[f], b = idx[f + 1], c = idx[f + 2];
        uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
        out.insert(out.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
    }
    idx = std::move(out);
}

// An icosphere with a smooth bumpy displacement (stands in when no bunny is installed).
void icosphere(std::vector<Vec3f>& p, std::vector<uint32_t>& idx) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    p = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    idx = {0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4,  11, 10, 2,  10, 7, 6, 7, 1, 8,
           3, 9,  4, 3, 4, 2, 3, 2, 6, 3, 6, 8,  3, 8,  9,  4, 9, 5, 2, 4,  11, 6,  2,  10, 8,  6, 7, 9, 8, 1};
}

}  // namespace

Result<ModelSource> generated_model(size_t target_triangles) {
    std::vector<Vec3f> p;
    std::vector<uint32_t> idx;
    std::string name;
    const char* bunny = "/usr/share/glmark2/models/bunny.obj";
    if (auto mesh = read_obj_merged(bunny); mesh) {
        for (const Vec3& v : mesh->positions) p.emplace_back(v);
        idx = mesh->indices;
        name = "bunny (subdivided)";
    } else {
        icosphere(p, idx);
        name = "bumpy sphere";
    }
    for (int k = subdivisions_toward(idx.size() / 3, target_triangles); k > 0; --k) subdivide(p, idx);
    if (name == "bumpy sphere")
        for (Vec3f& v : p) {
            Vec3f n = glm::normalize(v);
            v = n * (1.0f + 0.05f * std::sin(9.0f * n.x) * std::sin(7.0f * n.y) * std::sin(8.0f * n.z));
        }
    return ModelSource(name, Vec3f(0.85f, 0.62f, 0.55f), std::move(p), {}, std::move(idx));
}

int subdivisions_toward(size_t triangles, size_t target) {
    if (triangles == 0 || target == 0) return 0;
    // Each step multiplies the count by 4: taken while the count it gives is
    // nearer the target by ratio than the count before.
    int k = 0;
    const double t = static_cast<double>(target);
    for (double n = static_cast<double>(triangles); n * 4.0 / t < t / n; n *= 4.0) ++k;
    return k;
}

double frame_ms(render::Renderer& r, const render::View& camera, const render::FrameOptions& frame) {
    const auto t0 = std::chrono::steady_clock::now();
    r.render(camera, render::Lighting{}, frame);
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double cpu_now_ms() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace body::kiosk
