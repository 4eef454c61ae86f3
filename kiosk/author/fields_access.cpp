// Editors of the kiosk's access keys (SCENE.md): kiosk.high_contrast,
// kiosk.large_text, kiosk.access_buttons, kiosk.icons, each a true/false
// choice (fields_detail.h).
#include "kiosk/author/fields_detail.h"

namespace body::kiosk::author::detail {

namespace {

using scene::KioskSettings;
using scene::Scene;

constexpr char kHighContrast[] = "high contrast", kLargeText[] = "large text", kAccessButtons[] = "access buttons",
               kIcons[] = "icons";

// Field holds plain function pointers: the member and the label are template arguments.
template <bool KioskSettings::*Member, const char* Label>
Field bool_field(const char* key) {
    return {key,
            Label,
            FieldScope::Scene,
            FieldKind::Choice,
            [](const Scene& s, const FieldTarget&) { return std::string(s.kiosk.*Member ? "true" : "false"); },
            [](Scene& s, const FieldTarget&, const std::string& v) -> Status {
                if (v != "true" && v != "false") return input_error(std::string(Label) + ": true or false");
                s.kiosk.*Member = v == "true";
                return ok_status();
            },
            bool_choices};
}

}  // namespace

std::vector<Field> kiosk_access_fields() {
    return {bool_field<&KioskSettings::high_contrast, kHighContrast>("kiosk.high_contrast"),
            bool_field<&KioskSettings::large_text, kLargeText>("kiosk.large_text"),
            bool_field<&KioskSettings::access_buttons, kAccessButtons>("kiosk.access_buttons"),
            bool_field<&KioskSettings::icons, kIcons>("kiosk.icons")};
}

}  // namespace body::kiosk::author::detail
