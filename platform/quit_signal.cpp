// SIGINT/SIGTERM as a quit request (contract in quit_signal.h).
#include "platform/quit_signal.h"

#include <csignal>

namespace body::platform {
namespace {

volatile std::sig_atomic_t g_quit = 0;

void on_quit_signal(int signal) {
    if (g_quit) {
        std::signal(signal, SIG_DFL);
        std::raise(signal);
        return;
    }
    g_quit = 1;
}

}  // namespace

void install_quit_handlers() {
    g_quit = 0;
    std::signal(SIGINT, on_quit_signal);
    std::signal(SIGTERM, on_quit_signal);
}

bool quit_requested() { return g_quit != 0; }

void remove_quit_handlers() {
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
}

}  // namespace body::platform
