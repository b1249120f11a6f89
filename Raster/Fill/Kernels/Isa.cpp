// CPU-feature detection for the kernel ISAs, and their names.
#include "Raster/Fill/Kernels/Isa.hpp"

#include <cstdlib>

#include "Raster/Fill/Kernels/KernelConfig.hpp"

#if SR_KERNELS_X86 && defined(_MSC_VER) && !defined(__clang__)
#include <immintrin.h>
#include <intrin.h>
#endif

namespace sr {

const char* isaName(Isa isa) {
    switch (isa) {
    case Isa::Scalar: return "scalar";
    case Isa::Sse2: return "sse2";
    case Isa::Avx2: return "avx2";
    case Isa::Avx512: return "avx512";
    }
    return "?";
}

std::optional<Isa> parseIsa(std::string_view name) {
    if (name == "auto") return bestIsa();
    for (Isa isa : kAllIsas)
        if (name == isaName(isa)) return isa;
    return std::nullopt;
}

namespace {

struct CpuFeatures {
    bool sse2 = false, avx2 = false, avx512 = false;
};

CpuFeatures detect() {
    CpuFeatures f;
#if SR_KERNELS_X86
    f.sse2 = true; // the x86-64 baseline
#if defined(__GNUC__) || defined(__clang__)
    __builtin_cpu_init();
    // __builtin_cpu_supports includes the OS's YMM / ZMM state checks (XGETBV). The AVX2 and
    // AVX-512 kernels also count lanes with POPCNT (every AVX2 CPU has it; checked all the same).
    f.avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("popcnt");
    f.avx512 = f.avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
               __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl");
#else
    int info[4];
    __cpuid(info, 0);
    const int maxLeaf = info[0];
    __cpuid(info, 1);
    const bool osxsave = (info[2] & (1 << 27)) != 0, avx = (info[2] & (1 << 28)) != 0, popcnt = (info[2] & (1 << 23)) != 0;
    if (maxLeaf >= 7 && osxsave && avx) {
        const unsigned long long xcr0 = _xgetbv(0);
        __cpuidex(info, 7, 0);
        f.avx2 = (xcr0 & 6) == 6 && (info[1] & (1 << 5)) != 0 && popcnt;
        const unsigned ebx = unsigned(info[1]);
        const bool bits512 = (ebx & (1u << 16)) && (ebx & (1u << 17)) && (ebx & (1u << 30)) && (ebx & (1u << 31));
        f.avx512 = f.avx2 && (xcr0 & 0xE6) == 0xE6 && bits512; // F, DQ, BW, VL; opmask + ZMM state
    }
#endif
#endif
    return f;
}

const CpuFeatures& features() {
    static const CpuFeatures f = detect();
    return f;
}

bool envSet(const char* name) {
    const char* v = std::getenv(name);
    return v && *v && *v != '0';
}

} // namespace

bool isaAvailable(Isa isa) {
    switch (isa) {
    case Isa::Scalar: return true;
    case Isa::Sse2: return SR_KERNELS_X86 && features().sse2;
    case Isa::Avx2: return SR_KERNELS_X86 && features().avx2;
    case Isa::Avx512: return SR_KERNELS_X86 && features().avx512;
    }
    return false;
}

Isa bestIsa() {
    static const Isa best = [] {
        if (isaAvailable(Isa::Avx512) && !envSet("SR_NO_AVX512") && !envSet("SR_NO_AVX2")) return Isa::Avx512;
        if (isaAvailable(Isa::Avx2) && !envSet("SR_NO_AVX2")) return Isa::Avx2;
        if (isaAvailable(Isa::Sse2)) return Isa::Sse2;
        return Isa::Scalar;
    }();
    return best;
}

} // namespace sr
