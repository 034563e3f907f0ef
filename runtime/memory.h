// Where the runtime's memory comes from (issue 8): every buffer a pipeline takes at init goes
// through an Allocator, so an application can hand in its own allocate/release hooks or one
// block of memory of the size pipeline_memory_bytes() reports. Buffers are unique_ptr with a
// deleter that remembers its allocator. A frame allocates nothing.
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <type_traits>

namespace stipple {

struct Allocator {
    // nullptr: operator new (nothrow) / operator delete.
    void* (*allocate)(size_t bytes, void* user) = nullptr;
    void (*release)(void* pointer, void* user) = nullptr;  // nullptr with allocate: no release
    void* user = nullptr;
};

// Every allocation is rounded up to a multiple of this and aligned to it.
constexpr size_t kAllocationAlign = 16;
constexpr size_t rounded_allocation(size_t bytes) {
    return (bytes + kAllocationAlign - 1) / kAllocationAlign * kAllocationAlign;
}

// A hint to fetch the line holding p into the cache (loops over scattered data read a few
// items ahead); nothing where the compiler has no such builtin.
inline void prefetch_read(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p);
#else
    (void)p;
#endif
}

void* allocate_bytes(const Allocator& a, size_t bytes);  // nullptr on failure
void release_bytes(const Allocator& a, void* pointer);

// The allocator init-time allocations on this thread use (operator new unless a scope says
// otherwise). pipeline_init sets it from its argument for its duration.
const Allocator& current_allocator();
class AllocatorScope {
  public:
    explicit AllocatorScope(const Allocator& a);
    ~AllocatorScope();
    AllocatorScope(const AllocatorScope&) = delete;
    AllocatorScope& operator=(const AllocatorScope&) = delete;

  private:
    Allocator previous_;
};

struct BufferRelease {
    Allocator allocator;
    void operator()(void* pointer) const { release_bytes(allocator, pointer); }
};
template <typename T>
using Buffer = std::unique_ptr<T[], BufferRelease>;

// `count` (at least 1) default-constructed elements from the current allocator, or empty. The
// bytes are zeroed first, so every page under a buffer is touched at init: no frame is the first
// to write a page and pay the kernel's fault for it (tests/alloc/test_page_faults.cpp).
template <typename T>
Buffer<T> make_buffer(size_t count) {
    static_assert(std::is_trivially_destructible<T>::value, "buffers are released unrun");
    const Allocator& a = current_allocator();
    if (count == 0) count = 1;
    if (count > (SIZE_MAX - kAllocationAlign) / sizeof(T)) return Buffer<T>(nullptr, {a});
    void* raw = allocate_bytes(a, count * sizeof(T));
    if (!raw) return Buffer<T>(nullptr, {a});
    T* items = static_cast<T*>(raw);
    std::memset(raw, 0, count * sizeof(T));
    for (size_t i = 0; i < count; ++i) new (items + i) T;
    return Buffer<T>(items, {a});
}

template <typename T>
bool alloc(Buffer<T>* out, size_t count) {
    *out = make_buffer<T>(count);
    return *out != nullptr;
}

// A caller-provided block: allocations bump through it (16-byte aligned), release does nothing.
struct BlockArena {
    uint8_t* base = nullptr;
    size_t size = 0;
    size_t used = 0;
};
Allocator block_allocator(BlockArena* arena);

// Counts what allocations would take from a block (rounded sizes), while taking them from
// operator new so the counted work can run.
struct CountingArena {
    size_t bytes = 0;
};
Allocator counting_allocator(CountingArena* arena);

}  // namespace stipple
