// Patient orientation -> kiosk rotation (Euler X, Y, Z) and camera azimuths.
#include "builder/exhibit/orientation.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace body::exhibit {

Result<View> parse_view(const std::string& name) {
    if (name == "anterior") return View::Anterior;
    if (name == "left") return View::Left;
    if (name == "posterior") return View::Posterior;
    if (name == "right") return View::Right;
    return input_error("--view must be anterior|left|posterior|right, not '" + name + "'");
}

float view_azimuth_deg(View view) {
    switch (view) {
        case View::Anterior: return 0.0f;
        case View::Left: return 90.0f;
        case View::Posterior: return 180.0f;
        case View::Right: return -90.0f;
    }
    return 0.0f;
}

Result<std::array<Vec3, 3>> parse_orientation(const std::string& letters) {
    const std::string bad =
        "--orientation must be three letters from R/L, A/P, S/I (e.g. RAS, LPS), not '" + letters + "'";
    if (letters.size() != 3) return input_error(bad);
    std::array<Vec3, 3> axes;
    bool used[3] = {false, false, false};
    for (int i = 0; i < 3; ++i) {
        int axis = -1;
        double sign = 1.0;
        switch (std::toupper(static_cast<unsigned char>(letters[size_t(i)]))) {
            case 'R': axis = 0; break;
            case 'L': axis = 0, sign = -1.0; break;
            case 'A': axis = 1; break;
            case 'P': axis = 1, sign = -1.0; break;
            case 'S': axis = 2; break;
            case 'I': axis = 2, sign = -1.0; break;
            default: return input_error(bad);
        }
        if (used[axis]) return input_error(bad);
        used[axis] = true;
        axes[size_t(i)] = Vec3(0.0);
        axes[size_t(i)][axis] = sign;
    }
    return axes;
}

int mirror_axis(const std::array<Vec3, 3>& ras_axes) {
    if (glm::dot(glm::cross(ras_axes[0], ras_axes[1]), ras_axes[2]) >= 0.0) return -1;
    int k = 0;
    for (int i = 1; i < 3; ++i)
        if (std::fabs(ras_axes[size_t(i)].x) > std::fabs(ras_axes[size_t(k)].x)) k = i;
    return k;
}

std::array<std::array<double, 3>, 3> kiosk_rotation(const std::array<Vec3, 3>& ras_axes) {
    // Kiosk from RAS: X = left = -R, Y = superior, Z = anterior (det +1).
    const auto to_kiosk = [](const Vec3& ras) { return Vec3(-ras.x, ras.z, ras.y); };
    const std::array<Vec3, 3> col = {to_kiosk(ras_axes[0]), to_kiosk(ras_axes[1]), to_kiosk(ras_axes[2])};
    std::array<std::array<double, 3>, 3> m{};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) m[size_t(r)][size_t(c)] = col[size_t(c)][r];
    return m;
}

std::array<float, 3> kiosk_rotation_deg(const std::array<Vec3, 3>& ras_axes) {
    const auto m = kiosk_rotation(ras_axes);
    // M = Rz(c) * Ry(b) * Rx(a) (the kiosk applies X first).
    const double sb = std::clamp(-m[2][0], -1.0, 1.0);
    double a = 0.0, b = std::asin(sb), c = 0.0;
    if (std::fabs(sb) < 1.0 - 1e-9) {
        a = std::atan2(m[2][1], m[2][2]);
        c = std::atan2(m[1][0], m[0][0]);
    } else {
        // Gimbal lock: only a - c (b = 90) or a + c (b = -90) is defined; take c = 0.
        a = std::atan2(sb * m[0][1], m[1][1]);
    }
    const double deg = 180.0 / 3.14159265358979323846;
    const auto clean = [&](double r) {
        double d = std::round(r * deg * 1e4) / 1e4;  // exact quarter turns stay exact
        return static_cast<float>(d == 0.0 ? 0.0 : d);
    };
    return {clean(a), clean(b), clean(c)};
}

}  // namespace body::exhibit
