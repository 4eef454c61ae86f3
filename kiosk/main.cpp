// bodyview: the fullscreen GLES 3 kiosk.
#include <cstdio>
#include <string>

#include "body/version.h"
#include "platform/platform.h"
#include "shared/error.h"

namespace {

void print_help(std::FILE* out) {
    std::fprintf(out,
                 "bodyview %s - shows anatomy models on a touch screen (OpenGL ES 3.0)\n\n"
                 "usage: bodyview [options] [BUNDLE/]\n\noptions:\n"
                 "  --platform P  auto|glfw|drm|headless (compiled here:",
                 BODY_VERSION_STRING);
    for (auto b : body::platform::compiled_backends()) std::fprintf(out, " %s", body::platform::backend_name(b));
    std::fprintf(out,
                 ")\n  --help        this text\n  --version     print the version\n\n"
                 "exit codes: 0 ok, 1 runtime failure, 2 bad usage or bad input\n");
}

}  // namespace

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        if (a == "--help" || a == "-h") {
            print_help(stdout);
            return body::kExitOk;
        }
        if (a == "--version") {
            std::printf("bodyview %s\n", BODY_VERSION_STRING);
            return body::kExitOk;
        }
    }
    print_help(stderr);
    return body::kExitBadInput;
}
