// Picking over a body-scale scene: the nearest model under a ray by a walk over
// every model (what KioskApp::pick did) against the box hierarchy
// (shared/bvh.h, what it does now), in the same run on the same rays, with the
// same exact test per model: the ray against the model's triangles (a sphere
// of 960 triangles per model, as the kiosk's picker walks a model's level).
// Also the hierarchy's build and refit times. Times are thread CPU, best of 5.
//
// usage: bench_pick [--models N] [--rays N]   (defaults 2400 and 1000)
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "shared/bvh.h"

namespace {

using namespace body;

double cpu_seconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<uint32_t> indices;
};

Mesh unit_sphere(int rings, int segments) {
    Mesh m;
    for (int r = 0; r <= rings; ++r) {
        const float polar = float(M_PI) * float(r) / float(rings);
        for (int s = 0; s < segments; ++s) {
            const float az = 2.0f * float(M_PI) * float(s) / float(segments);
            m.positions.push_back({std::sin(polar) * std::cos(az), std::cos(polar), std::sin(polar) * std::sin(az)});
        }
    }
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = uint32_t(r * segments + s), b = uint32_t(r * segments + (s + 1) % segments);
            const uint32_t c = a + uint32_t(segments), d = b + uint32_t(segments);
            m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
        }
    }
    return m;
}

// Möller-Trumbore over every triangle: the nearest t >= 0 (object units along d).
std::optional<float> mesh_hit(const Mesh& m, const glm::vec3& o, const glm::vec3& d) {
    float best = 1e30f;
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3) {
        const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                        c = m.positions[m.indices[i + 2]];
        const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(d, e2);
        const float det = glm::dot(e1, p);
        if (std::fabs(det) < 1e-12f) continue;
        const float inv = 1.0f / det;
        const glm::vec3 s = o - a;
        const float u = glm::dot(s, p) * inv;
        if (u < 0.0f || u > 1.0f) continue;
        const glm::vec3 q = glm::cross(s, e1);
        const float v = glm::dot(d, q) * inv;
        if (v < 0.0f || u + v > 1.0f) continue;
        const float t = glm::dot(e2, q) * inv;
        if (t >= 0.0f && t < best) best = t;
    }
    return best < 1e30f ? std::optional<float>(best) : std::nullopt;
}

struct Scene {
    Mesh mesh;
    std::vector<glm::vec3> centre;
    std::vector<float> scale;
    std::optional<float> hit(size_t i, const Ray& r) const {
        // Into the model's frame (uniform scale): t scales back by the same factor.
        const auto t = mesh_hit(mesh, (r.origin - centre[i]) / scale[i], r.direction);
        return t ? std::optional<float>(*t * scale[i]) : std::nullopt;
    }
};

template <class F>
double best_of(int reps, F&& f) {
    double best = 1e30;
    for (int k = 0; k < reps; ++k) {
        const double t0 = cpu_seconds();
        f();
        best = std::min(best, cpu_seconds() - t0);
    }
    return best;
}

}  // namespace

int main(int argc, char** argv) {
    size_t models = 2400, rays = 1000;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--models")) models = std::strtoul(argv[i + 1], nullptr, 10);
        if (!std::strcmp(argv[i], "--rays")) rays = std::strtoul(argv[i + 1], nullptr, 10);
    }
    Scene scene;
    scene.mesh = unit_sphere(20, 24);  // 960 triangles
    std::mt19937 rng(29);
    std::uniform_real_distribution<float> jitter(-0.4f, 0.4f), radius(1.5f, 6.0f);
    const int side = int(std::ceil(std::cbrt(double(models))));
    std::vector<glm::vec3> lo(models), hi(models);
    for (size_t i = 0; i < models; ++i) {
        const int x = int(i) % side, y = int(i) / side % side, z = int(i) / (side * side);
        scene.centre.push_back(glm::vec3(x + jitter(rng), y + jitter(rng), z + jitter(rng)) * 10.0f);
        scene.scale.push_back(radius(rng));
        lo[i] = scene.centre[i] - scene.scale[i];
        hi[i] = scene.centre[i] + scene.scale[i];
    }
    // Rays from a viewpoint outside the scene towards random models (a visitor's taps).
    const glm::vec3 eye = glm::vec3(side * 5.0f, side * 5.0f, side * 30.0f);
    std::vector<Ray> ray_list;
    std::uniform_int_distribution<size_t> pick_model(0, models - 1);
    std::normal_distribution<float> aim(0.0f, 3.0f);
    for (size_t k = 0; k < rays; ++k) {
        const glm::vec3 target = scene.centre[pick_model(rng)] + glm::vec3(aim(rng), aim(rng), aim(rng));
        ray_list.push_back(Ray{eye, glm::normalize(target - eye)});
    }

    std::vector<int> brute_hit(rays), tree_hit(rays);
    const double brute = best_of(5, [&] {
        for (size_t k = 0; k < rays; ++k) {
            int best = -1;
            float best_t = 1e30f;
            for (size_t i = 0; i < models; ++i) {
                const auto t = scene.hit(i, ray_list[k]);
                if (t && *t < best_t) best_t = *t, best = int(i);
            }
            brute_hit[k] = best;
        }
    });
    Bvh bvh;
    const double build = best_of(5, [&] { bvh_build(bvh, lo, hi); });
    const double refit = best_of(5, [&] { bvh_refit(bvh, lo, hi); });
    size_t calls = 0;
    const double tree = best_of(5, [&] {
        calls = 0;
        for (size_t k = 0; k < rays; ++k) {
            float t = 0.0f;
            tree_hit[k] = bvh_nearest(
                bvh, ray_list[k],
                [&](uint32_t i) {
                    ++calls;
                    return scene.hit(i, ray_list[k]);
                },
                t);
        }
    });
    size_t differ = 0, hits = 0;
    for (size_t k = 0; k < rays; ++k) differ += brute_hit[k] != tree_hit[k], hits += brute_hit[k] >= 0;
    std::printf("pick over %zu models of %zu triangles, %zu rays (%zu hit a model), thread CPU, best of 5\n", models,
                scene.mesh.indices.size() / 3, rays, hits);
    std::printf("  every model (baseline): %10.1f us per pick\n", brute / double(rays) * 1e6);
    std::printf("  box hierarchy:          %10.1f us per pick  (%.4fx the baseline; %.1f models tested per pick)\n",
                tree / double(rays) * 1e6, tree / brute, double(calls) / double(rays));
    std::printf("  hierarchy build %.1f us, refit %.1f us; picks that differ from the baseline: %zu\n", build * 1e6,
                refit * 1e6, differ);
    return differ == 0 ? 0 : 1;
}
