// The one terminal progress bar of bodygen's long commands (contract in commands.h).
#include <cstdio>

#include "builder/cli/commands.h"

namespace body::cli {

std::function<void(size_t, size_t)> progress_bar(const char* unit) {
    return [unit](size_t done, size_t total) {
        constexpr int kWidth = 40;
        const int filled = total ? static_cast<int>(double(done) / double(total) * kWidth) : kWidth;
        std::fprintf(stderr, "\r[%.*s%*s] %zu/%zu %s", filled, "########################################",
                     kWidth - filled, "", done, total, unit);
        if (done >= total) std::fprintf(stderr, "\r%*s\r", kWidth + 60, "");
        std::fflush(stderr);
    };
}

}  // namespace body::cli
