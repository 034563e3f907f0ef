#include "runtime/thread_pool.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <new>
#include <thread>

namespace stipple {

struct ThreadPoolShared {
    std::mutex mutex;
    std::condition_variable start;  // a new task (generation moved) or stop
    std::condition_variable done;   // every range of the task finished
    // Under the mutex: the task of the current generation and how many of its ranges are done.
    uint64_t generation = 0;
    RangeTask task = nullptr;
    void* context = nullptr;
    uint32_t count = 0;
    int finished = 0;
    uint64_t worker_ranges = 0;  // ranges run by the workers, over the pool's life
    bool stop = false;
    // The ranges are claimed, not assigned: (generation << 8) | the next range to run. A thread
    // not scheduled yet (a loaded machine) leaves its range to whoever comes first, the caller
    // included, so a call never waits for a sleeping worker to start.
    std::atomic<uint64_t> claim{0};
    int threads = 1;
    std::thread workers[kMaxPoolThreads - 1];
};

namespace {

// Range k of [0, count) split into `threads` contiguous parts: the same parts whoever runs them.
inline void range_of(uint32_t count, int threads, int k, uint32_t* begin, uint32_t* end) {
    *begin = uint32_t(uint64_t(count) * uint64_t(k) / uint64_t(threads));
    *end = uint32_t(uint64_t(count) * uint64_t(k + 1) / uint64_t(threads));
}

// Runs ranges of `generation` while any is unclaimed; returns how many it ran. A thread that
// read an older generation's task claims nothing (the counter names the generation).
int run_ranges(ThreadPoolShared* s, uint64_t generation, RangeTask task, void* context,
               uint32_t count) {
    int ran = 0;
    for (;;) {
        uint64_t c = s->claim.load(std::memory_order_acquire);
        do {
            if ((c >> 8) != generation || int(c & 255u) >= s->threads) return ran;
        } while (!s->claim.compare_exchange_weak(c, c + 1, std::memory_order_acq_rel));
        uint32_t begin, end;
        range_of(count, s->threads, int(c & 255u), &begin, &end);
        if (begin < end) task(context, begin, end);
        ++ran;
    }
}

void worker_loop(ThreadPoolShared* s) {
    uint64_t seen = 0;
    for (;;) {
        RangeTask task;
        void* context;
        uint32_t count;
        {
            std::unique_lock<std::mutex> lock(s->mutex);
            s->start.wait(lock, [&] { return s->stop || s->generation != seen; });
            if (s->stop) return;
            seen = s->generation;
            task = s->task;
            context = s->context;
            count = s->count;
        }
        const int ran = run_ranges(s, seen, task, context, count);
        if (ran == 0) continue;
        std::lock_guard<std::mutex> lock(s->mutex);
        s->finished += ran;  // the caller waits for this generation until every range is in
        s->worker_ranges += uint64_t(ran);
        if (s->finished == s->threads) s->done.notify_one();
    }
}

}  // namespace

uint64_t thread_pool_worker_ranges(ThreadPool* pool) {
    if (!pool->shared) return 0;
    std::lock_guard<std::mutex> lock(pool->shared->mutex);
    return pool->shared->worker_ranges;
}

int thread_pool_auto_threads() {
    const unsigned hw = std::thread::hardware_concurrency();
    return hw == 0 ? 1 : int(std::min<unsigned>(hw, unsigned(kMaxAutoThreads)));
}

Status thread_pool_init(ThreadPool* pool, int threads) {
    thread_pool_destroy(pool);
    threads = std::max(1, std::min(threads, kMaxPoolThreads));
    if (threads == 1) return {};
    ThreadPoolShared* s = new (std::nothrow) ThreadPoolShared();
    if (!s) return make_status(StatusCode::out_of_memory, "out of memory for a thread pool");
    s->threads = threads;
    pool->shared = s;
    pool->threads = threads;
    for (int k = 1; k < threads; ++k) {
        // -fno-exceptions: a failed std::thread start terminates; the system's thread limit is
        // the only way it fails, and 64 threads are far below it.
        s->workers[k - 1] = std::thread(worker_loop, s);
    }
    return {};
}

void thread_pool_begin(ThreadPool* pool, uint32_t count, RangeTask task, void* context) {
    ThreadPoolShared* s = pool->shared;
    if (!s) {
        if (count > 0) task(context, 0, count);
        return;
    }
    {
        std::lock_guard<std::mutex> lock(s->mutex);
        const uint64_t generation = ++s->generation;
        s->task = task;
        s->context = context;
        s->count = count;
        s->finished = 0;
        s->claim.store(generation << 8, std::memory_order_release);
    }
    s->start.notify_all();
}

void thread_pool_finish(ThreadPool* pool) {
    ThreadPoolShared* s = pool->shared;
    if (!s) return;
    uint64_t generation;
    RangeTask task;
    void* context;
    uint32_t count;
    {
        std::lock_guard<std::mutex> lock(s->mutex);
        generation = s->generation;
        task = s->task;
        context = s->context;
        count = s->count;
    }
    const int ran = run_ranges(s, generation, task, context, count);
    std::unique_lock<std::mutex> lock(s->mutex);
    s->finished += ran;
    s->done.wait(lock, [&] { return s->finished == s->threads; });
}

void thread_pool_run(ThreadPool* pool, uint32_t count, uint32_t min_per_thread, RangeTask task,
                     void* context) {
    if (!pool->shared || count < uint64_t(min_per_thread) * 2u) {
        if (count > 0) task(context, 0, count);
        return;
    }
    thread_pool_begin(pool, count, task, context);
    thread_pool_finish(pool);
}

void thread_pool_destroy(ThreadPool* pool) {
    ThreadPoolShared* s = pool->shared;
    if (s) {
        {
            std::lock_guard<std::mutex> lock(s->mutex);
            s->stop = true;
        }
        s->start.notify_all();
        for (int k = 1; k < s->threads; ++k) s->workers[k - 1].join();
        delete s;
    }
    pool->shared = nullptr;
    pool->threads = 1;
}

}  // namespace stipple
