// ThreadPool's spin-wait hint and the count of usable hardware threads, kept here so that
// ThreadPool.hpp includes no intrinsics or system header.
#include "Raster/Frame/ThreadPool.hpp"

#if defined(__linux__)
#include <sched.h> // sched_getaffinity, CPU_COUNT
#endif

#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64) || defined(_M_IX86)
#include <immintrin.h> // _mm_pause
#endif

namespace sr {

int ThreadPool::usableHardwareThreads() {
#if defined(__linux__)
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) == 0) {
        const int n = CPU_COUNT(&set);
        if (n > 0) return n;
    }
#endif
    return int(std::thread::hardware_concurrency());
}

void ThreadPool::pause() {
#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64) || defined(_M_IX86)
    _mm_pause();
#else
    std::this_thread::yield();
#endif
}

} // namespace sr
