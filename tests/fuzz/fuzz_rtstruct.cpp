// libFuzzer target for the RT-STRUCT import (DCMTK parses a file, so each
// input is written to one temporary file per process): a contour stack or one
// error line naming the file, never a crash.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "builder/import/import.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = "/tmp/fuzz_rtstruct_" + std::to_string(::getpid()) + ".dcm";
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return 0;
    std::fwrite(data, 1, size, f);
    std::fclose(f);
    auto stack = body::import_rtstruct(path, {});
    if (!stack.ok()) {
        const std::string& m = stack.error().message;
        if (m.rfind(path, 0) != 0 || m.find('\n') != std::string::npos) std::abort();
    }
    return 0;
}
