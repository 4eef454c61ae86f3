// libFuzzer target: the contour stack parser must return a value or an error, never crash.
#include <cstddef>
#include <cstdint>
#include <string>

#include "builder/contours/contour_stack.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string text(reinterpret_cast<const char*>(data), size);
    auto stack = body::parse_contour_stack(text, "fuzz.json");
    if (stack.ok()) (void)body::contour_stack_to_json(*stack);
    return 0;
}
