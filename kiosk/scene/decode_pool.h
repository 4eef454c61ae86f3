#pragma once
// A fixed pool of decoding threads shared by every streamed file, so that a
// scene's loading scales with the machine's cores rather than with its files
// (a bundle of 2,000 models starts no more threads than one of 2).
//
// Threads: hardware_concurrency - 1, at least 1 (a core stays with the render
// thread while it compiles shaders and draws). They start at the first add()
// and run until the process exits.
//
// Tasks: a task is stepped by one pool thread at a time; each step does a
// bounded amount of work (a chunk of a file) and says what it needs next.
// Order: every task still decoding its base meshes comes before any task's
// detail, and among equals the higher priority first (the caller's estimate
// of the model's size on screen); detail runs only once release() was called
// for the task. A file is opened and read only while a thread steps it.
//
// Memory: a finished task frees its decoding scratch, and with thousands of
// small files those blocks lie scattered between the ones that stay, where
// glibc keeps them resident (it returns only a heap's top by itself: about
// 200 of 440 MiB of heap on a 2,088-model scene). So every kTrimEvery
// finished tasks, and whenever the threads go idle after finishing some, a
// pool thread hands the heaps' free pages back (malloc_trim); not before the
// first release() (the kiosk's first frame): until then the threads race the
// render thread to its first picture, and a trim's page returns interrupt
// every core (TLB shootdowns).
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace body::kiosk {

// What a task needs after a step.
enum class DecodeNeed {
    Bases,   // more work before its base meshes are in
    Detail,  // its bases are in; more work once released
    Paused,  // nothing wanted now; more work once woken (wake())
    Done,    // nothing more
};

class DecodeTask {
public:
    virtual ~DecodeTask() = default;
    // One bounded piece of work; `buffer` is the stepping thread's scratch
    // (reused across tasks). Called by one pool thread at a time.
    virtual DecodeNeed step(std::vector<uint8_t>& buffer) = 0;
};

class DecodePool {
public:
    // The process's pool.
    static DecodePool& shared();
    explicit DecodePool(size_t threads);
    ~DecodePool();  // joins the threads; every task must have been removed
    DecodePool(const DecodePool&) = delete;
    DecodePool& operator=(const DecodePool&) = delete;

    size_t threads() const { return thread_count_; }
    // Queues `task` (it needs its bases); it stays the caller's.
    void add(DecodeTask* task, double priority);
    // Lets the task's detail be decoded. Idempotent.
    void release(DecodeTask* task);
    // A paused task (its last step returned Paused, or the step in flight
    // will) is runnable again.
    void wake(DecodeTask* task);
    // Steps `task` on the calling thread when it still needs its bases and no
    // pool thread is stepping it (a caller that would wait for those bases
    // lends its core instead). False when it did not.
    bool step_here(DecodeTask* task, std::vector<uint8_t>& buffer);
    // Unqueues the task; blocks while a thread is stepping it. The pool does
    // not touch it after this returns.
    void remove(DecodeTask* task);

private:
    struct Entry {
        DecodeTask* task;
        double priority;
        DecodeNeed need = DecodeNeed::Bases;
        bool released = false, busy = false;
        bool woken = false;  // wake() while busy: a Paused from the step in flight counts as Detail
    };
    void run();
    void step(DecodeTask* task, std::vector<uint8_t>& buffer, std::unique_lock<std::mutex>& guard);
    Entry* find(DecodeTask* task);  // under mutex_
    Entry* next();                  // under mutex_: the runnable entry to step next, or nullptr
    void start();                   // under mutex_: the threads, at the first add()

    static constexpr size_t kTrimEvery = 64;
    void trim_freed_memory();  // without mutex_

    size_t thread_count_;
    size_t finished_since_trim_ = 0;  // under mutex_
    bool any_released_ = false;       // under mutex_: trims wait for the first release()
    std::mutex mutex_;
    std::condition_variable work_, idle_;
    std::vector<Entry> entries_;
    std::vector<std::thread> workers_;
    bool stop_ = false;
};

}  // namespace body::kiosk
