// dtlab's operator new: every buffer of 4 MiB or more asks the kernel for transparent huge pages
// before its first touch. A million-point run fills ~100 MB of such buffers (points in insertion
// order, the BRIO keys, the corner table, the hull and the output); with 4 KiB pages their
// page faults and TLB misses cost 15-25% of a one-core run, and which pages a repeated run got
// depended on where glibc's heap put its buffers, so timed runs in one process varied by up to
// 40%. Linux's default (transparent_hugepage=madvise) grants huge pages only on request, as here.
// Only a hint: with huge pages off, nothing changes. Not in sanitizer builds: their allocators
// pair each operator new with its own delete.
#include <cstdint>
#include <cstdlib>
#include <new>

#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
#define DLAB_SANITIZED_ALLOCATOR 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define DLAB_SANITIZED_ALLOCATOR 1
#endif

#if defined(__linux__) && !defined(DLAB_SANITIZED_ALLOCATOR)
#include <sys/mman.h>

void* operator new(std::size_t size) {
    void* p = std::malloc(size ? size : 1);
    if (!p) throw std::bad_alloc();
    constexpr std::size_t kLarge = std::size_t{4} << 20;
    constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
    if (size >= kLarge) {
        const auto at = reinterpret_cast<std::uintptr_t>(p);
        const std::uintptr_t begin = (at + kHuge - 1) & ~(kHuge - 1);
        const std::uintptr_t end = (at + size) & ~(kHuge - 1);
        madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
    }
    return p;
}
#endif
