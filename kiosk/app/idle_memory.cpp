// Giving the heap's free pages back after a reset (contract in idle_memory.h).
#include "kiosk/app/idle_memory.h"

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <utility>

namespace body::kiosk {
namespace {

void trim_heap() {
#ifdef __GLIBC__
    malloc_trim(0);  // every arena, free pages in the middle of a heap too
#endif
}

}  // namespace

IdleMemory::IdleMemory(std::function<void()> give_back, double delay)
    : give_back_(give_back ? std::move(give_back) : std::function<void()>(trim_heap)), delay_(delay) {}

void IdleMemory::frame(int resets, double now) {
    if (resets != resets_seen_) {
        resets_seen_ = resets;
        due_ = now + delay_;  // a second reset before it was due moves it on
    }
    if (due_ < 0.0 || now < due_) return;
    due_ = -1.0;
    give_back_();
    ++given_back_;
}

}  // namespace body::kiosk
