// The access modes' keys of `kiosk` (contract in scene_access.h).
#include "shared/scene/scene_access.h"

#include <nlohmann/json.hpp>

namespace body::scene::detail {

bool read_kiosk_access_settings(const nlohmann::json& k, const std::string& path, KioskSettings& out, Failure& f) {
    const std::pair<const char*, bool*> keys[] = {{"high_contrast", &out.high_contrast},
                                                  {"large_text", &out.large_text},
                                                  {"access_buttons", &out.access_buttons},
                                                  {"icons", &out.icons}};
    for (const auto& [key, value] : keys) {
        if (!k.contains(key)) continue;
        if (!k[key].is_boolean()) {
            f.where = path + "." + key;
            f.why = "expected true or false";
            return false;
        }
        *value = k[key].get<bool>();
    }
    return true;
}

}  // namespace body::scene::detail
