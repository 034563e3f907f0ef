// A small fixed pool of worker threads for the CPU point stages (issue 9 item 5: threads over
// point ranges). The workers are started in pipeline_init and joined in pipeline_destroy; a
// frame only wakes them, which takes no memory.
//
// Why it is race-free: thread_pool_run splits [0, count) into `threads` contiguous ranges, the
// same ones whoever runs them; the caller and the workers claim ranges from one atomic counter
// (each range is run exactly once, by whoever claims it first: a worker the system has not
// scheduled yet leaves its range to the caller). The task writes only the outputs of its own
// range (place: positions/normals of its points; relevance: their radii; size: their sizes)
// and reads what earlier, completed runs wrote. The hand-over goes through one mutex: the
// caller publishes the task under it, a worker reads the task under it before claiming, and
// reports the ranges it ran under it; the caller returns only when every range is reported.
// So everything written before the call happens-before the ranges read it, and everything a
// range wrote happens-before the caller returns. The claim counter carries the task's
// generation, so a worker still holding an older task claims nothing of a newer one. Each
// point's result is computed by the same code whatever range it falls into, so the output is
// byte-identical for any thread count.
#pragma once
#include <cstdint>

#include "runtime/status.h"

namespace stipple {

// What FrameConfig::threads = 0 resolves to at most: the hardware's threads, capped.
inline constexpr int kMaxAutoThreads = 8;
// The largest pool (FrameConfig::threads' limit).
inline constexpr int kMaxPoolThreads = 64;

// A task over points [begin, end) of the run.
using RangeTask = void (*)(void* context, uint32_t begin, uint32_t end);

struct ThreadPoolShared;  // runtime/thread_pool.cpp: the workers, mutex and condition variables

struct ThreadPool {
    int threads = 1;                     // the caller included
    ThreadPoolShared* shared = nullptr;  // null with one thread: tasks run on the caller
};

// Starts threads - 1 workers (none for 1). The pool's bookkeeping and the workers' stacks come
// from operator new and the system, not from the pipeline's Allocator (a 1-thread pool takes
// nothing). Fails with out_of_memory when the threads cannot be started.
[[nodiscard]] Status thread_pool_init(ThreadPool* pool, int threads);

// Runs task over [0, count) split into contiguous ranges, one per thread, and returns when
// every range is done. Runs on the caller alone when the pool has one thread or count is
// below min_per_thread * 2 (waking workers costs microseconds).
void thread_pool_run(ThreadPool* pool, uint32_t count, uint32_t min_per_thread, RangeTask task,
                     void* context);

// thread_pool_run in two halves, so the caller can do other work while the workers run:
// begin publishes the task's ranges and wakes the workers; finish runs the ranges no worker
// has claimed yet on the caller and returns when every range is done. Between the two the
// caller must not touch what the task reads or writes, nor use the pool. Without workers,
// begin runs the task itself. With count = 1 the whole task is one range, taken by the first
// worker to wake (pipeline_frame: the point stages beside the driver's mesh pass).
void thread_pool_begin(ThreadPool* pool, uint32_t count, RangeTask task, void* context);
void thread_pool_finish(ThreadPool* pool);

// Joins the workers; the pool is one thread again.
void thread_pool_destroy(ThreadPool* pool);

// How many ranges the workers (not the caller) have run since init: on a loaded machine the
// caller runs the ranges of workers that were not scheduled in time (benches report it).
uint64_t thread_pool_worker_ranges(ThreadPool* pool);

// The hardware's thread count, capped at kMaxAutoThreads (1 if unknown).
int thread_pool_auto_threads();

}  // namespace stipple
