// Cache hints: ask for a line before it is needed, so that its miss overlaps with other work.
#pragma once

namespace sr {

// The cache line holding `p` is about to be read (no effect where the compiler has no hint).
inline void prefetchForRead(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p, 0, 3);
#else
    (void)p;
#endif
}

// ... about to be read and written.
inline void prefetchForWrite(const void* p) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(p, 1, 3);
#else
    (void)p;
#endif
}

} // namespace sr
