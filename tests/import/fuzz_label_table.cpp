// libFuzzer target: the label table parser must return a value or an error, never crash.
#include <cstddef>
#include <cstdint>
#include <string>

#include "builder/import/label_table.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string text(reinterpret_cast<const char*>(data), size);
    auto table = body::parse_label_table(text, "fuzz.txt");
    if (table.ok()) {
        body::LabelTable copy;
        body::merge_label_table(copy, *table);
    }
    return 0;
}
