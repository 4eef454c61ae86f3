// libFuzzer target for the streaming (SAX) contour stack parser: it must
// return a stack or an error, never crash; an error is one line naming the
// file; a stack it accepts must survive writing and reading back unchanged;
// and validation of an accepted stack must not crash either.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "builder/contours/contour_stack.h"
#include "builder/contours/validate.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string text(reinterpret_cast<const char*>(data), size);
    auto stack = body::parse_contour_stack(text, "fuzz.json");
    if (!stack.ok()) {
        const std::string& m = stack.error().message;
        if (m.rfind("fuzz.json: ", 0) != 0 || m.find('\n') != std::string::npos) std::abort();
        return 0;
    }
    const std::string json = body::contour_stack_to_json(*stack);
    auto again = body::parse_contour_stack(json, "again.json");
    if (!again.ok() || body::contour_stack_to_json(*again) != json) std::abort();
    std::vector<std::string> warnings;
    (void)body::validate_contour_stack(*stack, "fuzz.json", warnings);
    return 0;
}
