#include "runtime/memory.h"

namespace stipple {
namespace {

thread_local Allocator g_current;

void* block_allocate(size_t bytes, void* user) {
    BlockArena* a = static_cast<BlockArena*>(user);
    const uintptr_t base = reinterpret_cast<uintptr_t>(a->base);
    const size_t pad = (kAllocationAlign - (base + a->used) % kAllocationAlign) % kAllocationAlign;
    const size_t need = rounded_allocation(bytes);
    if (a->used + pad > a->size || need > a->size - a->used - pad) return nullptr;
    void* p = a->base + a->used + pad;
    a->used += pad + need;
    return p;
}

void* counting_allocate(size_t bytes, void* user) {
    static_cast<CountingArena*>(user)->bytes += rounded_allocation(bytes);
    return ::operator new(rounded_allocation(bytes), std::nothrow);
}

void counting_release(void* pointer, void*) {
    ::operator delete(pointer);
}

}  // namespace

void* allocate_bytes(const Allocator& a, size_t bytes) {
    if (a.allocate) return a.allocate(rounded_allocation(bytes), a.user);
    return ::operator new(rounded_allocation(bytes), std::nothrow);
}

void release_bytes(const Allocator& a, void* pointer) {
    if (!pointer) return;
    if (a.allocate) {
        if (a.release) a.release(pointer, a.user);
        return;
    }
    ::operator delete(pointer);
}

const Allocator& current_allocator() {
    return g_current;
}

AllocatorScope::AllocatorScope(const Allocator& a) : previous_(g_current) {
    g_current = a;
}

AllocatorScope::~AllocatorScope() {
    g_current = previous_;
}

Allocator block_allocator(BlockArena* arena) {
    Allocator a;
    a.allocate = block_allocate;
    a.user = arena;
    return a;
}

Allocator counting_allocator(CountingArena* arena) {
    Allocator a;
    a.allocate = counting_allocate;
    a.release = counting_release;
    a.user = arena;
    return a;
}

}  // namespace stipple
