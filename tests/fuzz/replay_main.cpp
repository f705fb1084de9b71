// A main() for fuzz targets built without libFuzzer: replays corpus files as regression tests.
//
// Usage: fuzz_replay_TARGET PATH...  (files, or directories read recursively in sorted order).
// Every input runs through LLVMFuzzerTestOneInput; a failed property aborts (the CTest test
// fails and names the input on stderr). Outside sanitizer builds, operator new is counted too:
// an input whose largest single allocation exceeds kMaxAllocation fails, so that no reader
// sizes a buffer from what a header claims instead of from the bytes it holds.
#include "tests/fuzz/fuzz_common.h"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <new>
#include <string>
#include <vector>

#if defined(__SANITIZE_ADDRESS__)
#define DLAB_REPLAY_COUNTS_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DLAB_REPLAY_COUNTS_ALLOCATIONS 0
#endif
#endif
#ifndef DLAB_REPLAY_COUNTS_ALLOCATIONS
#define DLAB_REPLAY_COUNTS_ALLOCATIONS 1
#endif

namespace {

// 64 MiB: far above what any corpus input (a few KiB) legitimately needs, far below what a
// header's count could ask for (2^25 points are 512 MiB).
constexpr std::size_t kMaxAllocation = std::size_t{64} << 20;

std::atomic<std::size_t> g_largestAllocation{0};

}  // namespace

#if DLAB_REPLAY_COUNTS_ALLOCATIONS
// Replacing the global allocation functions is allowed in a program (not in a library): this
// file is only ever linked into the replay executables.
void* operator new(std::size_t size) {
    std::size_t seen = g_largestAllocation.load(std::memory_order_relaxed);
    while (size > seen && !g_largestAllocation.compare_exchange_weak(seen, size)) {}
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void* operator new[](std::size_t size) { return operator new(size); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
#endif

int main(int argc, char** argv) {
    namespace fs = std::filesystem;
    if (argc < 2) {
        std::fprintf(stderr, "usage: %s CORPUS_FILE_OR_DIR...\n", argv[0]);
        return 2;
    }
    std::vector<fs::path> inputs;
    for (int i = 1; i < argc; ++i) {
        const fs::path arg = argv[i];
        std::error_code ec;
        if (fs::is_directory(arg, ec)) {
            for (const auto& entry : fs::recursive_directory_iterator(arg)) {
                if (entry.is_regular_file()) inputs.push_back(entry.path());
            }
        } else if (fs::is_regular_file(arg, ec)) {
            inputs.push_back(arg);
        } else {
            std::fprintf(stderr, "%s: no such corpus file or directory\n", arg.c_str());
            return 2;
        }
    }
    std::sort(inputs.begin(), inputs.end());
    if (inputs.empty()) {
        std::fprintf(stderr, "no corpus inputs found: an empty corpus tests nothing\n");
        return 2;
    }
    std::size_t largest = 0;
    for (const fs::path& path : inputs) {
        std::ifstream in(path, std::ios::binary);
        const std::vector<char> bytes((std::istreambuf_iterator<char>(in)),
                                      std::istreambuf_iterator<char>());
        if (!in.eof() && in.fail()) {
            std::fprintf(stderr, "%s: cannot read\n", path.c_str());
            return 2;
        }
        // Named before running: an abort inside shows which input it was.
        std::fprintf(stderr, "replay %s (%zu bytes)\n", path.c_str(), bytes.size());
        g_largestAllocation = 0;
        LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
        const std::size_t peak = g_largestAllocation;
        largest = std::max(largest, peak);
        if (DLAB_REPLAY_COUNTS_ALLOCATIONS && peak > kMaxAllocation) {
            std::fprintf(stderr, "%s: one allocation of %zu bytes (the limit is %zu)\n",
                         path.c_str(), peak, kMaxAllocation);
            return 1;
        }
    }
    std::printf("replayed %zu inputs", inputs.size());
    if (DLAB_REPLAY_COUNTS_ALLOCATIONS)
        std::printf(", largest single allocation %zu bytes", largest);
    std::printf("\n");
    return 0;
}
