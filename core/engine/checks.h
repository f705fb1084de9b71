// DLAB_ASSERT(cond, msg): a precondition the hot paths rely on, checked in Debug and sanitizer
// builds (and wherever DLAB_CHECKS is defined), compiled out of release builds: there the
// condition is not evaluated at all. A failed check prints the file, line, condition and message
// on stderr and aborts: it is a bug in the engine, never a user's error.
#pragma once

#include <cstdio>
#include <cstdlib>

#if !defined(NDEBUG) || defined(DLAB_CHECKS)
#define DLAB_CHECKS_ON 1
#else
#define DLAB_CHECKS_ON 0
#endif

namespace dlab::detail {

[[noreturn]] inline void assertFailed(const char* cond, const char* msg, const char* file,
                                      int line) {
    std::fprintf(stderr, "%s:%d: DLAB_ASSERT(%s) failed: %s\n", file, line, cond, msg);
    std::abort();
}

}  // namespace dlab::detail

#if DLAB_CHECKS_ON
#define DLAB_ASSERT(cond, msg) \
    ((cond) ? (void)0 : ::dlab::detail::assertFailed(#cond, msg, __FILE__, __LINE__))
#else
#define DLAB_ASSERT(cond, msg) ((void)sizeof(!(cond)))
#endif
