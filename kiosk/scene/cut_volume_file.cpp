// The scene's grey-level volume to the renderer (contract in cut_volume_file.h).
#include "kiosk/scene/cut_volume_file.h"

#include <cstdio>

#include "shared/atomic_file.h"
#include "shared/scene/slice_volume.h"

namespace body::kiosk {

bool load_cut_volume(const scene::Scene& scene, render::Renderer& renderer) {
    const std::string& path = scene.cut_plane.volume_path;
    if (path.empty()) return false;
    auto fail = [](const std::string& why) {  // `why` names the file
        std::fprintf(stderr, "bodyview: cut plane volume skipped: %s\n", why.c_str());
        return false;
    };
    auto text = read_file(path);
    if (!text) return fail(text.error().message);
    auto volume = parse_slice_volume(
        std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text->data()), text->size()), path);
    if (!volume) return fail(volume.error().message);
    if (Status st = renderer.set_cut_volume(&*volume); !st) return fail(path + ": " + st.error().message);
    return true;
}

}  // namespace body::kiosk
