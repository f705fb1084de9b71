// The calling thread's stack mapped ahead of need: under an address-space limit (ulimit -v), a
// stack that has to grow after the heap took the rest dies of SIGSEGV, where the heap allocation
// itself would have thrown bad_alloc and been reported in one line.
#pragma once

#include <cstddef>

namespace dlab {

// Touches the next `bytes` of the stack below the caller's frame (one write a page), so that
// the kernel maps them now; they stay mapped for the life of the thread.
[[gnu::noinline]] inline void reserveStack(std::size_t bytes = std::size_t{1} << 20) {
    auto* p = static_cast<volatile char*>(__builtin_alloca(bytes));
    for (std::size_t i = 0; i < bytes; i += 4096) p[i] = 0;
    p[bytes - 1] = 0;
}

}  // namespace dlab
