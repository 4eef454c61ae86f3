// Distinct colours in OKLab and their greedy assignment to neighbouring structures.
// Reference: B. Ottosson, "A perceptual color space for image processing" (OKLab), 2020.
#include "builder/exhibit/palette.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace body::exhibit {
namespace {

double to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }
double to_srgb(double c) {
    c = std::clamp(c, 0.0, 1.0);
    return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

Vec3 oklab_from_srgb(const Vec3& s) {
    const double r = to_linear(s.x), g = to_linear(s.y), b = to_linear(s.z);
    const double l = std::cbrt(0.4122214708 * r + 0.5363325363 * g + 0.0514459929 * b);
    const double m = std::cbrt(0.2119034982 * r + 0.6806995451 * g + 0.1073969566 * b);
    const double q = std::cbrt(0.0883024619 * r + 0.2817188376 * g + 0.6299787005 * b);
    return {0.2104542553 * l + 0.7936177850 * m - 0.0040720468 * q,
            1.9779984951 * l - 2.4285922050 * m + 0.4505937099 * q,
            0.0259040371 * l + 0.7827717662 * m - 0.8086757660 * q};
}

Vec3 srgb_from_oklab(const Vec3& lab) {
    const double l = std::pow(lab.x + 0.3963377774 * lab.y + 0.2158037573 * lab.z, 3.0);
    const double m = std::pow(lab.x - 0.1055613458 * lab.y - 0.0638541728 * lab.z, 3.0);
    const double s = std::pow(lab.x - 0.0894841775 * lab.y - 1.2914855480 * lab.z, 3.0);
    return {to_srgb(4.0767416621 * l - 3.3077115913 * m + 0.2309699292 * s),
            to_srgb(-1.2684380046 * l + 2.6097574011 * m - 0.3413193965 * s),
            to_srgb(-0.0041960863 * l - 0.7034186147 * m + 1.7076147010 * s)};
}

}  // namespace

std::vector<Vec3> distinct_palette(size_t n) {
    // Candidates: light enough for shading to read, saturated enough to tell apart,
    // inside the sRGB gamut; then farthest-point sampling in OKLab (each next colour
    // the one farthest from all chosen), which keeps the closest pair as far apart
    // as this greedy can for every n.
    std::vector<Vec3> lab;
    for (double l : {0.58, 0.66, 0.74, 0.82})
        for (double c : {0.07, 0.11, 0.15})
            for (int h = 0; h < 48; ++h) {
                const double a = h * 7.5 * 3.14159265358979323846 / 180.0;
                const Vec3 candidate(l, c * std::cos(a), c * std::sin(a));
                const Vec3 rgb = srgb_from_oklab(candidate);
                if (glm::length(oklab_from_srgb(rgb) - candidate) < 1e-3) lab.push_back(candidate);  // in gamut
            }
    std::vector<Vec3> out;
    std::vector<double> nearest(lab.size(), 1e9);
    size_t pick = 0;
    for (size_t i = 1; i < lab.size(); ++i)  // start at the most saturated mid-light colour
        if (lab[i].x == 0.66 && std::hypot(lab[i].y, lab[i].z) > std::hypot(lab[pick].y, lab[pick].z)) pick = i;
    for (size_t k = 0; k < n; ++k) {
        out.push_back(srgb_from_oklab(lab[pick]));
        for (size_t i = 0; i < lab.size(); ++i) nearest[i] = std::min(nearest[i], glm::length(lab[i] - lab[pick]));
        pick = size_t(std::max_element(nearest.begin(), nearest.end()) - nearest.begin());
    }
    return out;
}

double colour_distance(const Vec3& a, const Vec3& b) { return glm::length(oklab_from_srgb(a) - oklab_from_srgb(b)); }

bool neighbours(const Box& a, const Box& b, double margin) {
    const double grow = margin * std::max(glm::length(a.hi - a.lo), glm::length(b.hi - b.lo));
    for (int k = 0; k < 3; ++k)
        if (a.lo[k] > b.hi[k] + grow || b.lo[k] > a.hi[k] + grow) return false;
    return true;
}

std::vector<Vec3> assign_colours(const std::vector<Box>& boxes, const std::vector<std::optional<Vec3>>& fixed) {
    const size_t n = boxes.size();
    std::vector<std::vector<size_t>> adj(n);
    for (size_t i = 0; i < n; ++i)
        for (size_t j = i + 1; j < n; ++j)
            if (neighbours(boxes[i], boxes[j])) adj[i].push_back(j), adj[j].push_back(i);
    std::vector<Vec3> out(n, Vec3(0.8));
    std::vector<bool> done(n, false);
    size_t open = 0;
    for (size_t i = 0; i < n; ++i) {
        if (i < fixed.size() && fixed[i]) {
            out[i] = *fixed[i];
            done[i] = true;
        } else {
            ++open;
        }
    }
    // Half again as many colours as structures: room to keep neighbours apart to the last one.
    const std::vector<Vec3> palette = distinct_palette(std::max<size_t>(open + open / 2, 1));
    std::vector<size_t> uses(palette.size(), 0);
    // Most neighbours first: they are the hardest to separate.
    std::vector<size_t> order;
    for (size_t i = 0; i < n; ++i)
        if (!done[i]) order.push_back(i);
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return adj[a].size() > adj[b].size(); });
    for (size_t i : order) {
        size_t best = 0;
        double best_score = -1.0;
        for (size_t c = 0; c < palette.size(); ++c) {
            double nearest = 10.0;  // no coloured neighbour: any colour is as good
            for (size_t j : adj[i])
                if (done[j]) nearest = std::min(nearest, colour_distance(palette[c], out[j]));
            // Unused colours first, then the farthest from the neighbours.
            const double score = nearest - 100.0 * double(uses[c]);
            if (score > best_score) best_score = score, best = c;
        }
        out[i] = palette[best];
        ++uses[best];
        done[i] = true;
    }
    return out;
}

}  // namespace body::exhibit
