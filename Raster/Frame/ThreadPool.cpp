// ThreadPool's spin-wait hint, kept here so that ThreadPool.hpp includes no intrinsics header.
#include "Raster/Frame/ThreadPool.hpp"

#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64) || defined(_M_IX86)
#include <immintrin.h> // _mm_pause
#endif

namespace sr {

void ThreadPool::pause() {
#if defined(__x86_64__) || defined(__i386__) || defined(_M_X64) || defined(_M_IX86)
    _mm_pause();
#else
    std::this_thread::yield();
#endif
}

} // namespace sr
