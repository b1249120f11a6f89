// Instruction sets the span kernels are built for, CPU-feature detection (the one place), and --isa names.
#pragma once

#include <optional>
#include <string_view>

namespace sr {

// Scalar is the readable reference loop (ScanlineFill.hpp's fillTriangle + the programs'
// fragment()); the others are the lane-width-generic kernels of Raster/Fill/Kernels/Kernels.inl
// instantiated for 4 (SSE2), 8 (AVX2, with POPCNT) and 16 (AVX-512 F/BW/DQ/VL) lanes. Every kernel is
// bit-identical to the scalar reference (Tests/Threads/KernelIdentityTests.cpp).
enum class Isa { Scalar, Sse2, Avx2, Avx512 };
inline constexpr Isa kAllIsas[] = {Isa::Scalar, Isa::Sse2, Isa::Avx2, Isa::Avx512};

// "scalar" | "sse2" | "avx2" | "avx512".
const char* isaName(Isa isa);
// The names above, and "auto" for bestIsa(); anything else: nullopt. Case-sensitive, as the
// other flag values.
std::optional<Isa> parseIsa(std::string_view name);

// True when this build has kernels for `isa` AND the CPU and OS support it (checked once:
// CPUID and the OS's saved register state, via __builtin_cpu_supports or CPUID + XGETBV).
bool isaAvailable(Isa isa);
// The widest available ISA. SR_NO_AVX2=1 in the environment caps it at SSE2 and SR_NO_AVX512=1 at
// AVX2 (for comparisons; an explicit --isa overrides both).
Isa bestIsa();

} // namespace sr
