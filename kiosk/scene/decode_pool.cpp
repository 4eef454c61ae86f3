// The shared decoding threads (contract in decode_pool.h).
#include "kiosk/scene/decode_pool.h"

#include <pthread.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>

namespace body::kiosk {

DecodePool& DecodePool::shared() {
    static DecodePool pool(std::max(std::thread::hardware_concurrency(), 2u) - 1);
    return pool;
}

DecodePool::DecodePool(size_t threads) : thread_count_(std::max<size_t>(threads, 1)) {}

DecodePool::~DecodePool() {
    {
        std::lock_guard guard(mutex_);
        stop_ = true;
    }
    work_.notify_all();
    for (std::thread& t : workers_) t.join();
}

void DecodePool::start() {
    if (!workers_.empty()) return;
    for (size_t i = 0; i < thread_count_; ++i) workers_.emplace_back([this] { run(); });
}

DecodePool::Entry* DecodePool::find(DecodeTask* task) {
    for (Entry& e : entries_)
        if (e.task == task) return &e;
    return nullptr;
}

// Bases before detail, then the higher priority; ties keep the order of add().
DecodePool::Entry* DecodePool::next() {
    Entry* best = nullptr;
    for (Entry& e : entries_) {
        if (e.busy || e.need == DecodeNeed::Done || e.need == DecodeNeed::Paused ||
            (e.need == DecodeNeed::Detail && !e.released))
            continue;
        if (!best || (e.need == DecodeNeed::Bases && best->need != DecodeNeed::Bases) ||
            (e.need == best->need && e.priority > best->priority))
            best = &e;
    }
    return best;
}

void DecodePool::add(DecodeTask* task, double priority) {
    {
        std::lock_guard guard(mutex_);
        start();
        entries_.push_back(Entry{task, priority});
    }
    work_.notify_one();
}

void DecodePool::release(DecodeTask* task) {
    {
        std::lock_guard guard(mutex_);
        Entry* e = find(task);
        if (!e || e->released) return;
        e->released = true;
        any_released_ = true;
    }
    work_.notify_one();
}

void DecodePool::wake(DecodeTask* task) {
    {
        std::lock_guard guard(mutex_);
        Entry* e = find(task);
        if (!e) return;
        if (e->busy)
            e->woken = true;
        else if (e->need == DecodeNeed::Paused)
            e->need = DecodeNeed::Detail;
        else
            return;
    }
    work_.notify_one();
}

void DecodePool::remove(DecodeTask* task) {
    std::unique_lock guard(mutex_);
    idle_.wait(guard, [&] {
        const Entry* e = find(task);
        return !e || !e->busy;
    });
    if (Entry* e = find(task)) {
        *e = entries_.back();
        entries_.pop_back();
    }
}

void DecodePool::run() {
    pthread_setname_np(pthread_self(), "bodyview-load");  // for top and perf
    std::vector<uint8_t> buffer;
    std::unique_lock guard(mutex_);
    for (;;) {
        Entry* e = nullptr;
        work_.wait(guard, [&] {
            if (stop_ || (e = next()) != nullptr) return true;
            if (finished_since_trim_ == 0 || !any_released_) return false;
            finished_since_trim_ = 0;  // idle after finishing tasks: their freed memory back now
            guard.unlock();
            trim_freed_memory();
            guard.lock();
            return stop_ || (e = next()) != nullptr;
        });
        if (stop_) return;
        step(e->task, buffer, guard);
        if (finished_since_trim_ >= kTrimEvery && any_released_) {
            finished_since_trim_ = 0;
            guard.unlock();
            trim_freed_memory();
            guard.lock();
        }
    }
}

void DecodePool::trim_freed_memory() {
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

// Under the lock, on an entry not busy: steps it with the lock released.
void DecodePool::step(DecodeTask* task, std::vector<uint8_t>& buffer, std::unique_lock<std::mutex>& guard) {
    find(task)->busy = true;
    guard.unlock();
    const DecodeNeed need = task->step(buffer);
    guard.lock();
    // Entries may have moved while unlocked (add, remove): look it up again.
    Entry* e = find(task);
    e->busy = false;
    e->need = need == DecodeNeed::Paused && e->woken ? DecodeNeed::Detail : need;
    e->woken = false;
    if (need == DecodeNeed::Done || need == DecodeNeed::Paused) ++finished_since_trim_;  // scratch freed
    idle_.notify_all();
}

bool DecodePool::step_here(DecodeTask* task, std::vector<uint8_t>& buffer) {
    std::unique_lock guard(mutex_);
    const Entry* e = find(task);
    if (!e || e->busy || e->need != DecodeNeed::Bases) return false;
    step(task, buffer, guard);
    return true;
}

}  // namespace body::kiosk
